"""The demo's one-page summary: self-contained HTML (images inline), no timestamps."""
from __future__ import annotations

from pathlib import Path

from stitchswitch import __version__
from stitchswitch.files.html_page import Figure, ItemList, Paragraph, Section, Table, code, inline, page


def _f(v, digits=2) -> str:
    return "" if v is None else f"{v:.{digits}f}"


def _inverse(built) -> str:
    parts = []
    for step in built.inverse:
        t = step.target
        bits = [f"h = {t['height_mm']:g} mm"]
        if t.get("radius_mm"):
            bits.append(f"r_a = {t['radius_mm']:g} mm")
        if t.get("max_diameter_mm"):
            bits.append(f"d <= {t['max_diameter_mm']:g} mm")
        if t.get("force_range_N"):
            lo, hi = t["force_range_N"]
            bits.append(f"force in [{lo:g}, {hi:g}] N")
        rows = [(k + 1, _f(c["d_mm"]), _f(c["fill"], 3), _f(c["h_mm"]), _f(c["r_a_mm"]),
                 _f(c["r_b_mm"]), _f(c["force_N"], 3), "chosen" if c == step.chosen else "")
                for k, c in enumerate(step.candidates)]
        parts.append(Section(f"{step.label}: {', '.join(bits)}", (
            Table(rows, head=("#", "d mm", "fill", "h mm", "r_a mm", "r_b mm", "force N", "")),),
            level=3))
    return parts


def _violations(violations):
    if not violations:
        return Paragraph("No violation: the design is clean.")
    rows = [(v.severity, v.rule, ", ".join(v.patches), _f(v.value), _f(v.limit), v.message)
            for v in violations]
    return Table(rows, head=("severity", "rule", "patches", "value mm", "limit mm", "message"))


def _fabrication(doc) -> list:
    g = doc.grouping
    head = (f"{g.hoopings} hooping(s) by {g.method} ({g.status}"
            + ("" if g.mip_gap is None else f", gap {g.mip_gap:g}")
            + f"); first-fit decreasing needs {g.first_fit_decreasing_hoopings}.")
    rows = [(h.number, h.hoop, ", ".join(p.id for p in h.patches), h.stitches,
             _f(h.time_min, 1), f"fabrication/{h.files.embroidery}") for h in doc.hoopings]
    return [Paragraph(head),
            Table(rows, head=("hooping", "hoop", "patches (in order)", "stitches", "min", "file"))]


def summary_html(demo, built, violations, fab_doc, outdir: Path) -> str:
    """The page; ``fab_doc`` the fabrication's ``FabricationDoc``, ``outdir`` the folder
    holding preview.png and patch.png."""
    design = built.design
    patches = [(p.id, p.piece, f"{p.centre_mm[0]:g}, {p.centre_mm[1]:g}", _f(p.diameter_mm),
                _f(p.fill, 4), p.conductive or "", p.state) for p in design.patches]
    files = ("design.json", "check.json", "preview.png", "preview.vtu", "patch.png",
             "fabrication/fabrication.html", "fabrication/fabrication.json")
    blocks = (
        Paragraph(demo.story),
        Paragraph(inline(f"stitchswitch {__version__}, demo ", code(demo.name), ", paper section "
                         f"{demo.paper_section}. Model predictions use the default material, "
                         "which is not fitted to fabricated samples (docs/model.md); switching "
                         "forces come from the polynomial model fitted to SYNTHETIC data "
                         "(docs/force.md)."), cls="note"),
        Section("1. Inverse design", (
            *_inverse(built),
            Paragraph("Every candidate is confirmed by a direct certified solve; the first is "
                      "used unless the demo checks a further property of its designs (its notes "
                      "say which).", cls="note"))),
        Section("2. Placement", (
            Table(patches, head=("patch", "piece", "centre mm (garment)", "d mm (stretched)",
                                 "fill", "conductive", "state")),
            ItemList(tuple(built.notes)))),
        Section("3. Constraint check", (_violations(violations),)),
        Section("4. Preview", (
            Figure((outdir / "preview.png").read_bytes(), "3D preview"),
            Figure((outdir / "patch.png").read_bytes(), "profile of the first patch"))),
        Section("5. Fabrication", (
            *_fabrication(fab_doc),
            Paragraph(inline(f"Stretch the fabric {fab_doc.stretch.eta:g}x in both directions "
                             "before hooping; the fabrication sheet (",
                             code("fabrication/fabrication.html"),
                             ") gives the steps, threads and alignment marks.")))),
        Section("Files", (ItemList(tuple(code(p) for p in files)),)),
    )
    return page(f"stitchswitch demo: {demo.title}", blocks, heading=demo.title)
