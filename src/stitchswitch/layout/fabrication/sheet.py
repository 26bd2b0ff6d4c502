"""The fabrication sheet: Markdown and a self-contained HTML page, both rendered from the
content of fabrication.json (``layout.fabrication.fabricate`` builds it), so the three always agree.

Sections: summary (machine, mode, grouping method, gap, bound), stretching and marking
instructions (paper, appendix A: 1.7x in both directions over one sheet of water-soluble
stabilizer, a drawn grid and pins), the hoopings in stitching order with hoop, turn, alignment
marks, threads (a conductive bobbin where a hooping has conductive triangles), stitch counts and
estimated times, the frame conflicts that could not be avoided, and the limits of the
estimates. The HTML page embeds the layout PNGs as data URIs (no external resources).
"""
from __future__ import annotations

import base64
import html

_CSS = """
body{font-family:-apple-system,Segoe UI,Helvetica,Arial,sans-serif;margin:0;background:#f7f8fa;color:#1d2329}
main{max-width:1000px;margin:0 auto;padding:24px 28px 40px;background:#fff}
h1{font-size:24px;margin:0 0 12px}h2{font-size:19px;margin-top:30px;border-bottom:1px solid #dde2e8;padding-bottom:4px}
h3{font-size:16px;margin-top:22px}
table{border-collapse:collapse;margin:8px 0;font-size:14px}
th,td{border:1px solid #d4dae1;padding:4px 8px;text-align:left;vertical-align:top}
th{background:#f0f2f5}
img{max-width:100%;border:1px solid #e1e5ea;margin:6px 0}
.note{color:#4b5561;font-size:13.5px}
.warn{background:#fff4e5;border-left:4px solid #e67e22;padding:6px 10px}
code{font-size:13px;background:#f0f2f5;padding:1px 4px;border-radius:3px}
footer{margin-top:30px;color:#6b7480;font-size:12.5px}
"""


def _f(v, digits: int = 1) -> str:
    return f"{v:.{digits}f}"


def _pt(p, digits: int = 1) -> str:
    return f"({_f(p[0], digits)}, {_f(p[1], digits)})"


def summary_rows(doc: dict) -> list[tuple[str, str]]:
    g, m = doc["grouping"], doc["machine"]
    gap = "n/a" if g["mip_gap"] is None else f"{100 * g['mip_gap']:.2f} %"
    rows = [("design", doc["design"]["file"]),
            ("machine", f"{m['label']} ({m['name']}, {m['source']})"),
            ("mode", doc["mode"]), ("format", doc["format"]),
            ("hoopings", str(len(doc["hoopings"]))),
            ("grouping", f"{g['method']} ({g['status']}); optimal: {'yes' if g['optimal'] else 'no'}; "
                         f"gap {gap}"),
            ("lower bound", f"{g['hoopings_lower_bound']} hooping(s)"),
            ("first-fit decreasing", f"{g['first_fit_decreasing_hoopings']} hooping(s)"),
            ("note", g["note"]),
            ("stitches", f"{doc['totals']['stitches']}"),
            ("sewing time", f"{_f(doc['totals']['time_min'])} min at "
                            f"{m['stitches_per_minute']:g} stitches/min (stitching only)")]
    if doc["mode"] == "free":
        rows.insert(5, ("spacing", f"{doc['grouping']['spacing_mm']:g} mm between patches"))
    return rows


def _thread_text(t: dict) -> str:
    if t["role"] == "conductive":
        return (f"conductive {t['colour']} (conductive thread in the bobbin for this block: "
                f"change the bobbin at the colour change) for {', '.join(t['patches'])}")
    return f"top {t['colour']} for {', '.join(t['patches'])}"


def _hooping_lines(h: dict, mode: str) -> list[str]:
    turn = "turned 90 degrees" if h["orientation_deg"] == 90 else "normal position"
    lines = [f"- hoop **{h['hoop']}** ({h['field_mm'][0]:g} x {h['field_mm'][1]:g} mm field, "
             f"{turn})"]
    if mode == "garment":
        lines.append(f"- piece `{h['piece']}`; field centre at {_pt(h['centre_garment_mm'])} mm "
                     f"on the relaxed piece, {_pt(h['centre_stretched_mm'])} mm stretched")
        marks = ", ".join(f"{n} {_pt(p)}" for n, p in zip(
            ("centre", "right", "top", "left", "bottom"), h["alignment_marks_garment_mm"]))
        lines.append(f"- alignment marks on the relaxed piece (mm), by hoop side: {marks}")
    lines.append(f"- file `{h['files']['embroidery']}`; layout `{h['files']['png']}`, "
                 f"`{h['files']['svg']}`")
    lines += [f"- thread: {_thread_text(t)}" for t in h["threads"]]
    lines.append(f"- {h['stitches']} stitches, {h['trims']} trims, {h['colour_changes']} colour "
                 f"change(s), {h['thread_length_m']:.2f} m of top thread, about "
                 f"{_f(h['time_min'])} min")
    return lines


def _patch_table(h: dict, mode: str) -> tuple[list[str], list[list[str]]]:
    head = ["#", "patch", "d (mm)", "fill", "hoop position (mm)"]
    if mode == "garment":
        head.append("garment centre (mm)")
    else:
        head.append("sew onto garment at (mm)")
    rows = []
    for p in h["patches"]:
        rows.append([str(p["order"]), p["id"], f"{p['diameter_mm']:g}", f"{p['fill']:g}",
                     _pt(p["position_hoop_mm"]), _pt(p["centre_garment_mm"])])
    return head, rows


def markdown(doc: dict) -> str:
    out = [f"# Fabrication sheet: {doc['design']['file']}", ""]
    out += ["| | |", "|---|---|"] + [f"| {k} | {v} |" for k, v in summary_rows(doc)] + [""]
    out += ["## Stretching and marking", ""]
    out += [f"{i}. {s}" for i, s in enumerate(doc["stretch"]["instructions"], start=1)] + [""]
    out += ["## Hoopings in stitching order", ""]
    out += ["| # | hoop | turn | patches | stitches | time (min) | file |",
            "|---|---|---|---|---|---|---|"]
    for h in doc["hoopings"]:
        out.append(f"| {h['number']} | {h['hoop']} | {h['orientation_deg']} deg | "
                   f"{', '.join(p['id'] for p in h['patches'])} | {h['stitches']} | "
                   f"{_f(h['time_min'])} | {h['files']['embroidery']} |")
    out.append("")
    for h in doc["hoopings"]:
        out += [f"### Hooping {h['number']}", ""] + _hooping_lines(h, doc["mode"]) + [""]
        head, rows = _patch_table(h, doc["mode"])
        out += ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
        out += ["| " + " | ".join(r) + " |" for r in rows]
        out += ["", f"![hooping {h['number']}]({h['files']['png']})", ""]
    out += ["## Frame conflicts", ""]
    out += _conflict_lines(doc) + [""]
    out += ["## Limits", ""] + [f"- {s}" for s in doc["limits"]] + [""]
    return "\n".join(out)


def _conflict_lines(doc: dict) -> list[str]:
    conf = doc["order"]["conflicts"]
    if doc["mode"] == "free":
        return ["None: every hooping is its own piece of fabric."]
    if not conf:
        return ["None: no hoop frame lands on a patch stitched before it."]
    how = ("the minimum for this grouping (exact order search)" if doc["order"]["exact"] else
           "minimised heuristically (too many hoopings for the exact search)")
    lines = [f"{len(conf)} place(s) where a frame lands on a patch stitched earlier; this is "
             f"{how}. Pad these patches (or hoop gently) when setting up the hooping:", ""]
    lines += [f"- hooping {c['hooping']}: the frame lands on patch {c['patch']} (stitched in "
              f"hooping {c['stitched_in_hooping']})" for c in conf]
    return lines


def html_page(doc: dict, images: dict[str, bytes]) -> str:
    e = lambda s: html.escape(str(s))  # noqa: E731
    uri = lambda name: "data:image/png;base64," + base64.b64encode(images[name]).decode("ascii")  # noqa: E731
    summary = "".join(f"<tr><th>{e(k)}</th><td>{e(v)}</td></tr>" for k, v in summary_rows(doc))
    steps = "".join(f"<li>{e(s)}</li>" for s in doc["stretch"]["instructions"])
    overview = (f'<img src="{uri(doc["files"]["overview_png"])}" alt="overview of the hoopings">'
                if doc["files"].get("overview_png") in images else "")
    order_rows = "".join(
        f"<tr><td>{h['number']}</td><td>{e(h['hoop'])}</td><td>{h['orientation_deg']} deg</td>"
        f"<td>{e(', '.join(p['id'] for p in h['patches']))}</td><td>{h['stitches']}</td>"
        f"<td>{_f(h['time_min'])}</td><td><code>{e(h['files']['embroidery'])}</code></td></tr>"
        for h in doc["hoopings"])
    sections = []
    for h in doc["hoopings"]:
        items = "".join(f"<li>{e(line[2:]).replace('**', '')}</li>"
                        for line in _hooping_lines(h, doc["mode"]))
        head, rows = _patch_table(h, doc["mode"])
        table = ("<table><tr>" + "".join(f"<th>{e(c)}</th>" for c in head) + "</tr>"
                 + "".join("<tr>" + "".join(f"<td>{e(c)}</td>" for c in r) + "</tr>" for r in rows)
                 + "</table>")
        img = h["files"]["png"]
        pic = f'<img src="{uri(img)}" alt="hooping {h["number"]} layout">' if img in images else ""
        sections.append(f"<h3>Hooping {h['number']}</h3><ul>{items.replace('`', '')}</ul>"
                        f"{table}{pic}")
    conflicts = "".join(f"<p>{e(line[2:] if line.startswith('- ') else line)}</p>"
                        for line in _conflict_lines(doc) if line)
    limits = "".join(f"<li>{e(s)}</li>" for s in doc["limits"])
    return f"""<!DOCTYPE html>
<html lang="en">
<head>
<meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1">
<title>Fabrication sheet: {e(doc['design']['file'])}</title>
<style>{_CSS}</style>
</head>
<body>
<main>
<h1>Fabrication sheet: {e(doc['design']['file'])}</h1>
<table>{summary}</table>
<h2>Stretching and marking</h2>
<ol>{steps}</ol>
<h2>Hoopings in stitching order</h2>
{overview}
<table><tr><th>#</th><th>hoop</th><th>turn</th><th>patches</th><th>stitches</th>
<th>time (min)</th><th>file</th></tr>{order_rows}</table>
{''.join(sections)}
<h2>Frame conflicts</h2>
<div class="{'warn' if doc['order']['conflicts'] else 'note'}">{conflicts}</div>
<h2>Limits</h2>
<ul class="note">{limits}</ul>
<footer>Generated by {e(doc['generator'])} {e(doc['version'])}; the numbers are in
fabrication.json.</footer>
</main>
</body>
</html>
"""
