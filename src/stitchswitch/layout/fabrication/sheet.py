"""The fabrication sheet: Markdown and a self-contained HTML page, both rendered from the
``FabricationDoc`` that fabrication.json is written from (``layout.fabrication.fabricate`` builds
it), so the three always agree.

Sections, in the order they are used in the workshop: a plain summary (what is made, how many
hoopings, how long), before you start (paper, appendix A: 1.7x in both directions over one
sheet of water-soluble stabilizer, a drawn grid and pins), what the drawings show (a legend of
every colour and mark), the hoopings in stitching order, each with why its hoop, numbered steps
(mark, stretch, hoop which way up, thread, every colour stop, unhoop; ``workshop``), its data
(hoop, turn, alignment marks, threads, stitch counts, times) and its drawing; the frame
conflicts with what to do about each; how the hoopings were found (the algorithm's figures, for
the record); and the limits of the estimates. The HTML page (``files.html_page``) embeds the
layout PNGs as data URIs (no external resources).
"""
from __future__ import annotations

from stitchswitch.files.html_page import Figure, ItemList, Paragraph, Section, Table, page
from stitchswitch.layout.embroidery.stitches import small_pieces_text
from stitchswitch.layout.fabrication.document import FabricationDoc, HoopingDoc, Thread
from stitchswitch.layout.fabrication.workshop import (
    LEGEND,
    conflict_advice,
    hooping_steps,
    method_rows,
    summary_rows,
)


def _f(v, digits: int = 1) -> str:
    return f"{v:.{digits}f}"


def _pt(p, digits: int = 1) -> str:
    return f"({_f(p[0], digits)}, {_f(p[1], digits)})"


_MARKDOWN_SPECIAL = set("\\`*_[]<>#!|~&")


def md_escape(text: str) -> str:
    """``text`` (an id or a name from the user's files) as literal Markdown: every character
    that Markdown or a table would interpret is backslash-escaped."""
    return "".join("\\" + c if c in _MARKDOWN_SPECIAL else c for c in str(text))


def _thread_text(t: Thread, esc=str) -> str:
    patches = ", ".join(map(esc, t.patches))
    colour = t.sheet_name()
    if t.role == "conductive":
        return (f"conductive {colour} (conductive thread in the bobbin for this block: "
                f"put the conductive bobbin in at the colour change before this block, and the "
                f"normal bobbin back when it ends) for {patches}")
    return f"top {colour} for {patches}"


def _hooping_lines(h: HoopingDoc, mode: str, esc=str) -> list[str]:
    turn = "turned 90 degrees" if h.orientation_deg == 90 else "normal position"
    lines = [f"- hoop **{h.hoop}** ({h.field_mm[0]:g} x {h.field_mm[1]:g} mm field, {turn}); "
             f"why this hoop: {esc(h.hoop_reason)}"] if h.hoop_reason else \
        [f"- hoop **{h.hoop}** ({h.field_mm[0]:g} x {h.field_mm[1]:g} mm field, {turn})"]
    if mode == "garment":
        piece = f"`{h.piece}`" if esc is str else esc(h.piece)
        lines.append(f"- piece {piece}; field centre at {_pt(h.centre_garment_mm)} mm "
                     f"on the relaxed piece, {_pt(h.centre_stretched_mm)} mm stretched")
        marks = ", ".join(f"{n} {_pt(p)}" for n, p in zip(
            ("centre", "right", "top", "left", "bottom"), h.alignment_marks_garment_mm))
        lines.append(f"- alignment marks on the relaxed piece (mm), by hoop side: {marks}")
    lines.append(f"- file `{h.files.embroidery}`; layout `{h.files.png}`, `{h.files.svg}`")
    if h.files.template_a4:
        lines.append(f"- 1:1 template to print at 100 % and mark through: `{h.files.template_a4}` "
                     f"(A4) or `{h.files.template_letter}` (Letter); check its 50 mm square")
    lines += [f"- thread: {_thread_text(t, esc)}" for t in h.threads]
    lines.append(f"- {h.stitches} stitches, {h.trims} trims, {h.colour_changes} colour "
                 f"change(s), {h.thread_length_m:.2f} m of top thread, about "
                 f"{_f(h.time_min)} min")
    if h.small_pieces:
        lines.append(f"- warning: {small_pieces_text(h.small_pieces)}")
    if h.gap_crossings:
        lines.append(f"- {h.gap_crossings} thread crossing(s) over unstitched fabric "
                     f"({h.gap_crossing_mm:.1f} mm of thread): clip them after stitching")
    return lines


def _patch_table(h: HoopingDoc, mode: str, esc=str) -> tuple[list[str], list[list[str]]]:
    head = ["#", "patch", "d (mm)", "fill", "hoop position (mm)"]
    if mode == "garment":
        head.append("garment centre (mm)")
    else:
        head.append("sew onto garment at (mm)")
    rows = [[str(p.order), esc(p.id), f"{p.diameter_mm:g}", f"{p.fill:g}", _pt(p.position_hoop_mm),
             _pt(p.centre_garment_mm)] for p in h.patches]
    return head, rows


ORDER_HEAD = ("#", "hoop", "turn", "patches", "stitches", "time (min)", "file")


def _order_row(h: HoopingDoc, esc=str) -> tuple[str, ...]:
    return (str(h.number), h.hoop, f"{h.orientation_deg} deg", ", ".join(esc(p.id) for p in h.patches),
            str(h.stitches), _f(h.time_min), h.files.embroidery)


def _md_table(head, rows) -> list[str]:
    return (["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
            + ["| " + " | ".join(r) + " |" for r in rows])


def markdown(doc: FabricationDoc) -> str:
    esc = md_escape
    out = [f"# Fabrication sheet: {esc(doc.design.file)}", ""]
    out += ["| | |", "|---|---|"] + [f"| {k} | {v} |" for k, v in summary_rows(doc, esc)] + [""]
    out += ["## Before you start", ""]
    out += [f"{i}. {s}" for i, s in enumerate(doc.stretch.instructions, start=1)] + [""]
    out += ["## What the drawings show", ""] + _md_table(("you see", "it means"), LEGEND) + [""]
    out += ["## Hoopings in stitching order", ""]
    out += _md_table(ORDER_HEAD, [_order_row(h, esc) for h in doc.hoopings])
    out.append("")
    for h in doc.hoopings:
        out += [f"### Hooping {h.number}", ""]
        out += [f"{i}. {s}" for i, s in enumerate(hooping_steps(h, doc, esc), start=1)] + [""]
        out += _hooping_lines(h, doc.mode, esc) + [""]
        out += _md_table(*_patch_table(h, doc.mode, esc))
        out += ["", f"![hooping {h.number}]({h.files.png})", ""]
    out += ["## Frame conflicts", ""]
    out += _conflict_lines(doc, esc) + [""]
    out += ["## How the hoopings were found", ""]
    out += ["| | |", "|---|---|"] + [f"| {k} | {v} |" for k, v in method_rows(doc)] + [""]
    out += ["## Limits", ""] + [f"- {s}" for s in doc.limits] + [""]
    return "\n".join(out)


def _conflict_lines(doc: FabricationDoc, esc=str) -> list[str]:
    conf = doc.conflicts
    if doc.mode == "free":
        return ["None: every hooping is its own piece of fabric."]
    if not conf:
        return ["None: no hoop frame lands on a patch stitched before it."]
    how = ("the fewest possible over the hoop positions tried (exhaustive search of hoopings "
           "and order)" if doc.grouping.conflicts_exact else
           "the fewest found (a beam search over hoopings and order; not proven the fewest)")
    lines = [f"{len(conf)} place(s) where a frame lands on a patch stitched earlier; this is "
             f"{how}. What to do at each:", ""]
    lines += [f"- {conflict_advice(c, esc)}" for c in conf]
    return lines


def _plain(line: str) -> str:
    """A Markdown list line as plain text: no bullet, no bold or code markers."""
    return line[2:].replace("**", "").replace("`", "")


def html_page(doc: FabricationDoc, images: dict[str, bytes]) -> str:
    """The sheet as one self-contained HTML page; ``images``: PNG bytes by file name."""
    def picture(name: str, alt: str) -> tuple:
        return (Figure(images[name], alt),) if name in images else ()

    hoopings = []
    for h in doc.hoopings:
        head, rows = _patch_table(h, doc.mode)
        hoopings.append(Section(f"Hooping {h.number}", (
            ItemList(tuple(s.replace("`", "") for s in hooping_steps(h, doc)), ordered=True),
            ItemList(tuple(_plain(line) for line in _hooping_lines(h, doc.mode))),
            Table(tuple(rows), head=tuple(head)),
            *picture(h.files.png, f"hooping {h.number} layout")), level=3))
    conflicts = _conflict_lines(doc)
    cls = "warn" if doc.conflicts else "note"
    blocks = (
        Table(tuple(summary_rows(doc)), keys=True),
        Section("Before you start", (ItemList(doc.stretch.instructions, ordered=True),)),
        Section("What the drawings show", (Table(LEGEND, head=("you see", "it means")),)),
        Section("Hoopings in stitching order", (
            *picture(doc.overview_png, "overview of the hoopings"),
            Table(tuple(_order_row(h) for h in doc.hoopings), head=ORDER_HEAD), *hoopings)),
        Section("Frame conflicts", (Paragraph(conflicts[0], cls=cls),) + (
            (ItemList(tuple(line[2:] for line in conflicts[2:]), cls=cls),)
            if len(conflicts) > 2 else ())),
        Section("How the hoopings were found", (Table(tuple(method_rows(doc)), keys=True),)),
        Section("Limits", (ItemList(doc.limits, cls="note"),)),
    )
    return page(f"Fabrication sheet: {doc.design.file}", blocks,
                footer=f"Generated by {doc.generator} {doc.version}; the numbers are in "
                       "fabrication.json.")
