"""The per-hooping stitch-plan preview of Fabrication Mode: the needle path of one hooping's
stitch plan (``layout.fabrication.plan.plan_hooping``, the plan ``fabricate`` writes to its
machine file) as SVG in hoop mm: the hoop's sewing field, each thread's stitches as a polyline
in its colour (a jump or trim starts a new polyline; jumps are drawn dotted grey), with the
stitch, jump, trim and colour-change counts and the sewing time.
"""
from __future__ import annotations

from html import escape

import numpy as np

from stitchswitch.layout.embroidery.stitches import COLOR_CHANGE, JUMP, STITCH, TRIM

PAD_MM = 5.0


def _f(v: float) -> str:
    return f"{v:.2f}"


def _hex(rgb) -> str:
    return "#" + "".join(f"{int(c):02x}" for c in rgb)


def runs(plan):
    """[(thread index, (n, 2) stitch points)]: the plan's needle path cut at every jump, trim
    and colour change, each run with the thread it is sewn in."""
    out, thread, run = [], 0, []
    last = None
    for (x, y), cmd in zip(plan.xy_mm, plan.commands):
        if cmd == STITCH:
            if not run and last is not None:
                run.append(last)
            run.append((x, y))
        else:
            if len(run) > 1:
                out.append((thread, np.array(run)))
            run = []
            if cmd == COLOR_CHANGE:
                thread += 1
        last = (x, y)
    if len(run) > 1:
        out.append((thread, np.array(run)))
    return out


def counts(plan) -> dict:
    c = plan.commands
    return {"stitches": int(np.count_nonzero(c == STITCH)), "jumps": int(np.count_nonzero(c == JUMP)),
            "trims": int(np.count_nonzero(c == TRIM)),
            "colour_changes": int(np.count_nonzero(c == COLOR_CHANGE)),
            "minutes": round(float(plan.sewing_time_min), 1)}


def plan_svg(plan, hooping, label: str = "") -> str:
    """SVG of ``plan`` (hoop mm, y up) inside ``hooping``'s sewing field."""
    w, h = hooping.hoop.field_mm(0)            # the plan is in the hoop's own axes
    x0, y0 = -w / 2 - PAD_MM, -h / 2 - PAD_MM
    out = [f'<svg xmlns="http://www.w3.org/2000/svg" viewBox="{_f(x0)} {_f(y0)} {_f(w + 2 * PAD_MM)} '
           f'{_f(h + 2 * PAD_MM)}" width="100%" style="background:#fff" data-stitch-plan="1">',
           f'<rect x="{_f(-w / 2)}" y="{_f(-h / 2)}" width="{_f(w)}" height="{_f(h)}" fill="none" '
           'stroke="#1f77b4" stroke-width="0.6" stroke-dasharray="4 2"/>']
    xy, cmd = plan.xy_mm, plan.commands
    for i in np.flatnonzero(cmd == JUMP):
        if i > 0:
            (ax, ay), (bx, by) = xy[i - 1], xy[i]
            out.append(f'<line x1="{_f(ax)}" y1="{_f(-ay)}" x2="{_f(bx)}" y2="{_f(-by)}" '
                       'stroke="#aaa" stroke-width="0.2" stroke-dasharray="1 1"/>')
    for thread, pts in runs(plan):
        colour = _hex(plan.threads[min(thread, len(plan.threads) - 1)].rgb) if plan.threads else "#000"
        path = " ".join(f"{_f(x)},{_f(-y)}" for x, y in pts)
        out.append(f'<polyline data-run="{thread}" points="{path}" fill="none" stroke="{colour}" '
                   'stroke-width="0.25"/>')
    if label:
        out.append(f'<text x="{_f(x0 + 1)}" y="{_f(y0 + 4)}" font-size="4" fill="#333">'
                   f'{escape(label)}</text>')
    out.append("</svg>")
    return "".join(out)
