"""The demo's one-page summary: self-contained HTML (images inline), no timestamps."""
from __future__ import annotations

import base64
import html
from pathlib import Path

from stitchswitch import __version__

CSS = """body{font-family:system-ui,sans-serif;max-width:1000px;margin:2em auto;padding:0 1em;
color:#222}h1{font-size:1.6em}h2{border-bottom:1px solid #ccc;padding-bottom:.2em;margin-top:1.6em}
table{border-collapse:collapse;margin:.6em 0}td,th{border:1px solid #ccc;padding:.25em .6em;
text-align:left;font-size:.92em}th{background:#f3f3f3}img{max-width:100%;border:1px solid #ddd}
.note{color:#555;font-size:.92em}code{background:#f5f5f5;padding:0 .2em}"""


def _e(value) -> str:
    return html.escape(str(value))


def _img(path: Path, alt: str) -> str:
    data = base64.b64encode(path.read_bytes()).decode("ascii")
    return f'<img src="data:image/png;base64,{data}" alt="{_e(alt)}">'


def _table(head, rows) -> str:
    return ("<table><tr>" + "".join(f"<th>{_e(h)}</th>" for h in head) + "</tr>"
            + "".join("<tr>" + "".join(f"<td>{_e(c)}</td>" for c in r) + "</tr>" for r in rows)
            + "</table>")


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
                 _f(c["r_b_mm"]), _f(c["force_N"], 3), "chosen" if k == 0 else "")
                for k, c in enumerate(step.candidates)]
        parts.append(f"<h3>{_e(step.label)}: {_e(', '.join(bits))}</h3>"
                     + _table(("#", "d mm", "fill", "h mm", "r_a mm", "r_b mm", "force N", ""),
                              rows))
    return "".join(parts)


def _violations(violations) -> str:
    if not violations:
        return "<p>No violation: the design is clean.</p>"
    rows = [(v.severity, v.rule, ", ".join(v.patches), _f(v.value), _f(v.limit), v.message)
            for v in violations]
    return _table(("severity", "rule", "patches", "value mm", "limit mm", "message"), rows)


def _fabrication(doc: dict) -> str:
    g = doc["grouping"]
    head = (f"<p>{g['hoopings']} hooping(s) by {_e(g['method'])} ({_e(g['status'])}"
            + ("" if g.get("mip_gap") is None else f", gap {g['mip_gap']:g}")
            + f"); first-fit decreasing needs {g['first_fit_decreasing_hoopings']}.</p>")
    rows = [(h["number"], h["hoop"], ", ".join(p["id"] for p in h["patches"]), h["stitches"],
             _f(h["time_min"], 1), f"fabrication/{h['files']['embroidery']}")
            for h in doc["hoopings"]]
    return head + _table(("hooping", "hoop", "patches (in order)", "stitches", "min", "file"),
                         rows)


def summary_html(demo, built, violations, fab_doc: dict, outdir: Path) -> str:
    design = built.design
    patches = [(p.id, p.piece, f"{p.centre_mm[0]:g}, {p.centre_mm[1]:g}", _f(p.diameter_mm),
                _f(p.fill, 4), p.conductive or "", p.state) for p in design.patches]
    notes = "".join(f"<li>{_e(n)}</li>" for n in built.notes)
    files = "".join(f"<li><code>{_e(p)}</code></li>" for p in
                    ("design.json", "check.json", "preview.png", "preview.vtu", "patch.png",
                     "fabrication/fabrication.html", "fabrication/fabrication.json"))
    return f"""<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8">
<title>stitchswitch demo: {_e(demo.title)}</title><style>{CSS}</style></head><body>
<h1>{_e(demo.title)}</h1>
<p>{_e(demo.story)}</p>
<p class="note">stitchswitch {_e(__version__)}, demo <code>{_e(demo.name)}</code>, paper section
{_e(demo.paper_section)}. Model predictions use the default material, which is not fitted to
fabricated samples (docs/model.md); switching forces come from the polynomial model fitted to
SYNTHETIC data (docs/force.md).</p>
<h2>1. Inverse design</h2>{_inverse(built)}
<p class="note">Every candidate is confirmed by a direct certified solve; the first is used.</p>
<h2>2. Placement</h2>{_table(("patch", "piece", "centre mm (garment)", "d mm (stretched)",
                               "fill", "conductive", "state"), patches)}
<ul>{notes}</ul>
<h2>3. Constraint check</h2>{_violations(violations)}
<h2>4. Preview</h2>{_img(outdir / "preview.png", "3D preview")}
{_img(outdir / "patch.png", "profile of the first patch")}
<h2>5. Fabrication</h2>{_fabrication(fab_doc)}
<p>Stretch the fabric {fab_doc['stretch']['eta']:g}x in both directions before hooping; the
fabrication sheet (<code>fabrication/fabrication.html</code>) gives the steps, threads and
alignment marks.</p>
<h2>Files</h2><ul>{files}</ul>
</body></html>
"""
