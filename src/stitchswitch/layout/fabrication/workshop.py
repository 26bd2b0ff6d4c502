"""The fabrication sheet's plain-language parts, written for the person at the machine.

Built from the ``FabricationDoc`` (``document``), so they say exactly what fabrication.json
holds: the summary without algorithm terms (``summary_rows``), what every colour and mark of the
drawings and templates means (``LEGEND``), per hooping the steps in order (``hooping_steps``:
mark, stretch, hoop which way up, thread, what to do at each colour stop, what to do after),
the reason for its hoop (``HoopingDoc.hoop_reason``), what to do about each frame conflict
(``conflict_advice``), and, for the record at the end, how the grouping was found
(``method_rows``). ``layout.fabrication.sheet`` lays them out as Markdown and HTML.
"""
from __future__ import annotations

from stitchswitch.layout.fabrication.document import Conflict, FabricationDoc, HoopingDoc

__all__ = ["LEGEND", "summary_rows", "method_rows", "orientation_text", "colour_stops",
           "hooping_steps", "conflict_advice"]

#: (what you see, what it means) for the hooping drawings (hoopNN.png/svg), the overview and
#: the 1:1 templates (hoopNN-template-*.pdf) and marks (hoopNN-marks.dxf)
LEGEND = (
    ("grey band", "the hoop frame: it clamps the fabric there (drawings)"),
    ("solid black rectangle", "the sewing field: the needle reaches everything inside it"),
    ("dashed rectangle inside it", "the margin: no stitch is placed between it and the field edge"),
    ("red cross", "the centre mark: put the hoop template's centre on it"),
    ("red triangles / red + marks", "the side marks at the middle of each field side: line up "
                                    "the hoop template's side marks with them"),
    ("coloured triangles with '1. id'", "this hooping's patches in their thread colours, "
                                        "numbered in the order the machine sews them (the order "
                                        "in the file)"),
    ("filled grey disc", "a patch stitched in an earlier hooping"),
    ("dotted circle", "a patch still to be stitched in a later hooping"),
    ("red disc", "a patch stitched earlier that this hooping's frame lands on (a frame "
                 "conflict: see Frame conflicts)"),
    ("light blue area", "the piece (drawings: stretched, hoop mm; templates: relaxed, 1:1)"),
    ("blue rectangle (templates)", "the sewing field on the relaxed piece"),
    ("dashed grey rectangle (templates)", "the outer edge of the hoop frame on the relaxed piece"),
    ("green circles (templates)", "the patches' footprints on the relaxed piece, with their ids"),
    ("50 mm square (templates)", "measure it: if it is not 50 mm the page was scaled; print "
                                 "at 100 %"),
    ("numbered rectangles (overview)", "every hooping's field (solid) and frame (dotted), "
                                       "numbered in stitching order"),
)


def summary_rows(doc: FabricationDoc, esc=str) -> list[tuple[str, str]]:
    """The sheet's first table: what is made, on what, in how many hoopings and how long."""
    m, t = doc.machine, doc.totals
    conf = len(doc.conflicts)
    rows = [("design", esc(doc.design.file)),
            ("machine", f"{m.label}, files in {doc.embroidery_format.upper()} format"),
            ("what you do", "stitch the patches on the garment pieces, one hooping after the "
                            "other" if doc.mode == "garment" else
                            "stitch the patches on separate fabric, cut them out and sew "
                            "them on"),
            ("hoopings", f"{t.hoopings}, in the order below" + _extra_hoopings(doc)),
            ("patches", str(t.patches)),
            ("stitches", f"{t.stitches}, about {t.time_min:.0f} min of stitching at "
                         f"{m.stitches_per_minute:g} stitches/min (hooping not counted)"),
            ("frame on a stitched patch", "never" if not conf else
             f"{conf} time(s): pad those patches (see Frame conflicts)")]
    if doc.mode == "free":
        rows.insert(4, ("spacing", f"{doc.grouping.spacing_mm:g} mm between patches"))
    return rows


def _extra_hoopings(doc: FabricationDoc) -> str:
    """Why the plan has more hoopings than the fewest possible, if it has."""
    g = doc.grouping
    if g.fewest_hoopings is None or doc.totals.hoopings <= g.fewest_hoopings:
        return ""
    more = doc.totals.hoopings - g.fewest_hoopings
    return (f": {more} more than the fewest possible ({g.fewest_hoopings}), because with "
            f"{g.fewest_hoopings} a hoop frame would land on a stitched patch "
            f"{g.fewest_hoopings_conflicts} time(s), which can crush it")


def _proof(g) -> str:
    return ("proven the fewest over the hoop positions tried, by exhaustive search"
            if g.conflicts_exact else "the fewest a beam search found, not proven")


def method_rows(doc: FabricationDoc) -> list[tuple[str, str]]:
    """How the hoopings were found, for the record (the numbers behind the plan)."""
    g = doc.grouping
    gap = "n/a" if g.mip_gap is None else f"{100 * g.mip_gap:.2f} %"
    proof = ("proven the fewest possible over the hoop positions tried" if g.optimal else
             "not proven the fewest")
    return [("method", f"{g.method} (HiGHS status {g.status}, gap {gap}): {proof}"),
            ("fewest hoopings possible", f"at least {g.hoopings_lower_bound}"),
            ("simple packing (first-fit decreasing)",
             f"{g.first_fit_decreasing_hoopings} hooping(s)"),
            ("hoop positions tried", str(g.candidates)),
            *([("frame conflicts", f"{len(doc.conflicts)}, planned before the number of "
                f"hoopings ({_proof(g)}); the fewest hoopings ({g.fewest_hoopings}) would "
                f"leave {g.fewest_hoopings_conflicts}")] if g.fewest_hoopings is not None
              else []),
            ("stitching order", "the order with the fewest frame conflicts (exhaustive)"
             if doc.order_exact else "greedy (too many hoopings for the exhaustive order)"),
            ("note", g.note)]


def orientation_text(h: HoopingDoc) -> str:
    """Which way the piece lies in the hoop (the hoop's y axis points away from you)."""
    if h.piece is None:
        return "any way up (a separate piece of fabric)"
    if h.orientation_deg == 90:
        return ("turned a quarter: the hoop lies across the piece, the pattern's up (+y) "
                "pointing to your right and its +x towards you")
    return "straight: the pattern's up (+y) pointing away from you and its +x to your right"


def _role(t) -> str:
    return "conductive" if t.role == "conductive" else "top"


def colour_stops(h: HoopingDoc, esc=str) -> list[str]:
    """What to do before sewing and at every colour stop of the hooping's file, in order; each
    thread named as the sheet names it (for a JEF, the palette thread the machine shows)."""
    threads = h.threads
    names = [t.sheet_name() for t in threads]
    out = []
    first = threads[0]
    bobbin = ("the conductive bobbin in" if first.role == "conductive" else "a normal bobbin in")
    out.append(f"Thread {names[0]} on top, {bobbin}; the machine sews "
               f"{', '.join(map(esc, first.patches))}.")
    for k, (prev, nxt) in enumerate(zip(threads, threads[1:]), start=1):
        name = names[k]
        if nxt.role == "conductive" and prev.role != "conductive":
            action = ("take the normal bobbin out and put the conductive bobbin in (the paper "
                      f"sews conductive regions with conductive thread in the bobbin); top "
                      f"thread {name}")
        elif prev.role == "conductive" and nxt.role != "conductive":
            action = f"put the normal bobbin back; top thread {name}"
        else:
            action = f"change the top thread to {name}"
        out.append(f"Colour stop {k}: {action}; the machine then sews "
                   f"{', '.join(map(esc, nxt.patches))} ({_role(nxt)} thread).")
    last = threads[-1]
    if last.role == "conductive":
        out.append("When the file ends: put the normal bobbin back for the next hooping.")
    return out


def conflict_advice(c: Conflict, esc=str) -> str:
    """Which frame, which patch, what to do."""
    return (f"hooping {c.hooping}: its frame lands on patch {esc(c.patch)}, stitched in "
            f"hooping {c.stitched_in_hooping}. Before clamping, lay a folded cloth or foam "
            f"strip over {esc(c.patch)} under the frame (or float it: clamp only the "
            "stabilizer there) so the frame does not crush the patch or mark the fabric.")


def hooping_steps(h: HoopingDoc, doc: FabricationDoc, esc=str) -> list[str]:
    """The numbered steps of one hooping, from marking to unhooping."""
    steps = []
    if h.piece is not None:
        marks = []
        if h.files.template_a4:
            marks.append(f"print `{h.files.template_a4}` (A4) or `{h.files.template_letter}` "
                         "(Letter) at 100 % (check the 50 mm square), lay it on the relaxed "
                         "piece with the outlines matching")
        if h.files.marks_dxf:
            marks.append(f"or cut/plot the marks from `{h.files.marks_dxf}` (relaxed mm, 1:1)")
        steps.append(f"Mark: {'; '.join(marks) or 'mark the alignment points listed below'}; "
                     "mark the centre cross and the four side marks on the piece.")
        steps.append(f"Stretch the piece {doc.stretch.eta:g}x both ways over the stabilizer "
                     "(Before you start).")
        steps.append(f"Hoop it in the {h.hoop}, {orientation_text(h)}; the hoop template's "
                     "centre and side marks on the marks of step 1.")
    else:
        steps.append(f"Stretch a fresh piece of fabric {doc.stretch.eta:g}x both ways over the "
                     f"stabilizer and hoop it in the {h.hoop}, centred.")
    mine = [c for c in doc.conflicts if c.hooping == h.number]
    if mine:
        steps.append("Pad before clamping: " + " ".join(
            f"the frame lands on {esc(c.patch)} (stitched in hooping {c.stitched_in_hooping})."
            for c in mine) + " Lay a folded cloth or foam strip over it under the frame.")
    steps.append(f"Load `{h.files.embroidery}` on the machine.")
    steps += colour_stops(h, esc)
    after = "Unhoop"
    if h.gap_crossings:
        after = (f"Clip the {h.gap_crossings} thread crossing(s) over unstitched fabric "
                 f"({h.gap_crossing_mm:.0f} mm of thread), then unhoop")
    steps.append(f"{after}; the patches pop up when the fabric is released.")
    return steps
