"""The 2D canvas as SVG markup: the pieces to scale with a 50 mm grid and their names, the
patches as their relaxed footprints (diameter d / eta) with ids, filled by predicted height,
the selection, patches named by a check violation, and in Fabrication Mode the hoopings with
their order. ``to_mm`` maps a pointer position on the drawn SVG back to garment mm.

Garment y points up; the SVG's y points down, so y is negated (the viewBox is in mm).
"""
from __future__ import annotations

from dataclasses import dataclass
from html import escape

import numpy as np
from matplotlib import colormaps
from matplotlib.colors import Normalize, to_hex

MARGIN_MM = 20.0
GRID_MM = 50.0
STATUS_STROKE = {"error": "#d62728", "warning": "#ff9e24"}


@dataclass(frozen=True)
class View:
    """The viewBox (x0, y0, width, height) in SVG units (mm, y negated)."""
    x0: float
    y0: float
    width: float
    height: float


def view_of(design) -> View:
    pts = np.vstack([p.outline_mm for p in design.pieces])
    lo, hi = pts.min(axis=0) - MARGIN_MM, pts.max(axis=0) + MARGIN_MM
    return View(float(lo[0]), float(-hi[1]), float(hi[0] - lo[0]), float(hi[1] - lo[1]))


def to_mm(view: View, px: float, py: float, width_px: float, height_px: float) -> tuple[float, float]:
    """Garment mm of pointer (px, py) on an SVG drawn at width_px x height_px with the default
    preserveAspectRatio (xMidYMid meet)."""
    scale = min(width_px / view.width, height_px / view.height)
    ox = (width_px - view.width * scale) / 2.0
    oy = (height_px - view.height * scale) / 2.0
    x = view.x0 + (px - ox) / scale
    y = view.y0 + (py - oy) / scale
    return float(x), float(-y)


def _f(v: float) -> str:
    return f"{v:.2f}"


def _height_colour(h, hmax: float) -> str:
    if h is None:
        return "#bbbbbb"
    return to_hex(colormaps["coolwarm"](Normalize(-hmax, hmax)(h)))


def svg(design, heights: dict, eta: float, selected: str | None = None, status: dict | None = None,
        hoopings=()) -> str:
    """The canvas of ``design``; ``heights``: {patch id: h mm or None}; ``status``: {patch id:
    "error" | "warning"}; ``hoopings``: ((hoop rectangle corners (4, 2) garment mm, label), ...)."""
    v = view_of(design)
    status = status or {}
    out = [f'<svg xmlns="http://www.w3.org/2000/svg" viewBox="{_f(v.x0)} {_f(v.y0)} {_f(v.width)} '
           f'{_f(v.height)}" width="100%" height="100%" style="background:#fafafa">']
    gx = np.arange(np.ceil(v.x0 / GRID_MM), np.floor((v.x0 + v.width) / GRID_MM) + 1) * GRID_MM
    gy = np.arange(np.ceil(v.y0 / GRID_MM), np.floor((v.y0 + v.height) / GRID_MM) + 1) * GRID_MM
    out += [f'<line x1="{_f(x)}" y1="{_f(v.y0)}" x2="{_f(x)}" y2="{_f(v.y0 + v.height)}" '
            'stroke="#e4e4e4" stroke-width="0.5"/>' for x in gx]
    out += [f'<line x1="{_f(v.x0)}" y1="{_f(y)}" x2="{_f(v.x0 + v.width)}" y2="{_f(y)}" '
            'stroke="#e4e4e4" stroke-width="0.5"/>' for y in gy]
    for piece in design.pieces:
        pts = " ".join(f"{_f(x)},{_f(-y)}" for x, y in piece.outline_mm)
        out.append(f'<polygon points="{pts}" fill="#ffffff" stroke="#222" stroke-width="1"/>')
        c = np.asarray(piece.outline_mm).mean(axis=0)
        out.append(f'<text x="{_f(c[0])}" y="{_f(-c[1])}" font-size="10" fill="#888" '
                   f'text-anchor="middle">{escape(piece.name)}</text>')
    known = [abs(h) for h in heights.values() if h is not None]
    hmax = max(known + [1.0])
    for p in design.patches:
        r = p.diameter_mm / (2.0 * eta)
        x, y = p.centre_mm
        stroke = STATUS_STROKE.get(status.get(p.id), "#333")
        width = 3 if p.id == selected else (2 if p.id in status else 0.8)
        dash = ' stroke-dasharray="4 2"' if p.id == selected else ""
        out.append(f'<circle data-patch="{escape(p.id)}" cx="{_f(x)}" cy="{_f(-y)}" r="{_f(r)}" '
                   f'fill="{_height_colour(heights.get(p.id), hmax)}" fill-opacity="0.85" '
                   f'stroke="{stroke}" stroke-width="{width}"{dash}/>')
        out.append(f'<text x="{_f(x)}" y="{_f(-y + 3)}" font-size="9" text-anchor="middle" '
                   f'pointer-events="none">{escape(p.id)}</text>')
    for corners, label in hoopings:
        pts = " ".join(f"{_f(x)},{_f(-y)}" for x, y in corners)
        out.append(f'<polygon points="{pts}" fill="none" stroke="#1f77b4" stroke-width="1.2" '
                   'stroke-dasharray="6 3" pointer-events="none"/>')
        out.append(f'<text x="{_f(corners[0][0] + 3)}" y="{_f(-corners[0][1] - 3)}" font-size="10" '
                   f'fill="#1f77b4" pointer-events="none">{escape(label)}</text>')
    out.append("</svg>")
    return "".join(out)
