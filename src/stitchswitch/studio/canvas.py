"""The 2D canvas as SVG markup: the pieces to scale with a 50 mm grid and their names, mm
rulers along the top and left edges, the patches as their relaxed footprints (diameter d / eta)
with ids, filled by predicted height, the selection, patches named by a check violation, while
a patch is dragged the piece-edge rule's lines (``guides``), and in Fabrication Mode the
hoopings with their order. ``svg`` draws it as one SVG; ``layers`` as three drawn one over
the other (the grid and pieces, the patches, the rulers), so that the page replaces only the
patches' markup on an edit; ``patches_svg`` is that layer alone. ``to_mm`` maps a pointer
position on the drawn SVG back to garment mm; ``zoomed`` and ``panned`` move the view.

Garment y points up; the SVG's y points down, so y is negated (the viewBox is in mm).
"""
from __future__ import annotations

from dataclasses import dataclass
from html import escape

import numpy as np
import shapely
from matplotlib import colormaps
from matplotlib.colors import Normalize, to_hex

MARGIN_MM = 20.0
GRID_MM = 50.0
STATUS_STROKE = {"error": "#d62728", "warning": "#ff9e24"}
BACKGROUND = "#fafafa"


@dataclass(frozen=True)
class View:
    """The viewBox (x0, y0, width, height) in SVG units (mm, y negated)."""
    x0: float
    y0: float
    width: float
    height: float


#: the zoom range, relative to the view that fits the pieces
ZOOM_RANGE = (0.05, 4.0)


def view_of(design) -> View:
    """The view that fits every piece with a margin."""
    pts = np.vstack([p.outline_mm for p in design.pieces])
    lo, hi = pts.min(axis=0) - MARGIN_MM, pts.max(axis=0) + MARGIN_MM
    return View(float(lo[0]), float(-hi[1]), float(hi[0] - lo[0]), float(hi[1] - lo[1]))


def zoomed(view: View, factor: float, about_mm, fit: View) -> View:
    """``view`` magnified by ``factor`` (> 1 zooms in) keeping the garment point ``about_mm``
    where it is on the screen; its size stays within ``ZOOM_RANGE`` of the ``fit`` view's."""
    lo, hi = ZOOM_RANGE
    scale = float(np.clip(view.width / factor, fit.width * lo, fit.width * hi)) / view.width
    ax, ay = float(about_mm[0]), -float(about_mm[1])
    return View(ax - (ax - view.x0) * scale, ay - (ay - view.y0) * scale,
                view.width * scale, view.height * scale)


def panned(view: View, dx_mm: float, dy_mm: float) -> View:
    """``view`` moved so that the garment shifts by (dx_mm, dy_mm) on the screen."""
    return View(view.x0 - float(dx_mm), view.y0 + float(dy_mm), view.width, view.height)


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


def _height_colours(heights, hmax: float) -> list[str]:
    """The fill of each height (None: grey), one colour-map call for all."""
    known = np.array([0.0 if h is None else h for h in heights], dtype=float)
    rgba = colormaps["coolwarm"](Normalize(-hmax, hmax)(known)) if known.size else []
    return ["#bbbbbb" if h is None else to_hex(c) for h, c in zip(heights, rgba)]


def _ruler_step(width_mm: float) -> float:
    """Labelled ruler step: the first of 10, 50, 100, 500 mm giving at most ~12 labels."""
    return next((s for s in (10.0, 50.0, 100.0, 500.0) if width_mm / s <= 12), 1000.0)


def _ruler_axis(axis: str, lo: float, length: float, edge: float, step: float, band: float,
                size: float) -> list[str]:
    """The ticks (every step / 5) and labels (every step) of one ruler: ``axis`` "x" runs
    along the top edge (SVG y = ``edge``), "y" down the left edge (SVG x = ``edge``); ``lo``
    and ``length``: the view's extent along the axis in SVG units. Labels are garment mm (the
    SVG's y is the garment's negated)."""
    minor = step / 5
    sign = 1.0 if axis == "x" else -1.0

    def at(along: float, across: float) -> tuple[str, str]:
        return (_f(along), _f(across)) if axis == "x" else (_f(across), _f(along))

    out = []
    for t in np.arange(np.ceil(lo / minor), np.floor((lo + length) / minor) + 1) * minor:
        major = abs(t / step - round(t / step)) < 1e-9
        tick = band * (0.6 if major else 0.3)
        (x1, y1), (x2, y2) = at(t, edge + band - tick), at(t, edge + band)
        out.append(f'<line x1="{x1}" y1="{y1}" x2="{x2}" y2="{y2}" stroke="#666" '
                   f'stroke-width="{_f(band / 20)}" pointer-events="none"/>')
        if major:
            tx, ty = (at(t + band * 0.1, edge + size) if axis == "x"
                      else at(t - band * 0.1, edge + band * 0.05))
            value = sign * t + 0.0
            out.append(f'<text x="{tx}" y="{ty}" font-size="{_f(size if axis == "x" else size * 0.8)}" '
                       f'fill="#444" pointer-events="none" data-ruler-{axis}="{value:g}">{value:g}</text>')
    return out


def rulers(v: View) -> list[str]:
    """mm rulers along the top and left edges of the view (ticks every step / 5, labels every
    step), drawn in garment mm so that they follow zoom and pan; x and y as in the design file."""
    step = _ruler_step(max(v.width, v.height))
    band = v.height * 0.035
    size = band * 0.6
    out = [f'<rect x="{_f(v.x0)}" y="{_f(v.y0)}" width="{_f(v.width)}" height="{_f(band)}" '
           'fill="#f0f0f0" pointer-events="none" data-ruler="x"/>',
           f'<rect x="{_f(v.x0)}" y="{_f(v.y0)}" width="{_f(band)}" height="{_f(v.height)}" '
           'fill="#f0f0f0" pointer-events="none" data-ruler="y"/>']
    out += _ruler_axis("x", v.x0, v.width, v.y0, step, band, size)
    out += _ruler_axis("y", v.y0, v.height, v.x0, step, band, size)
    out.append(f'<text x="{_f(v.x0 + band * 0.1)}" y="{_f(v.y0 + size)}" '
               f'font-size="{_f(size * 0.8)}" fill="#444" pointer-events="none">mm</text>')
    return out


def guides(design, patch_ids, eta: float, limits) -> list[str]:
    """The piece-edge rule for dragged patches, as dashed lines on their pieces: the seam line
    (the seam allowance inside the outline) and, per patch, where its centre must stay (seam
    allowance + edge clearance + its relaxed radius inside the outline)."""
    from stitchswitch.layout.check.rules.footprint import garment_radius_mm

    out = []
    for pid in patch_ids:
        p = design.patch(pid)
        poly = shapely.make_valid(shapely.Polygon(design.piece(p.piece).outline_mm))
        for inset, colour, kind in ((limits.seam_allowance_mm, "#888", "seam"),
                                    (limits.seam_allowance_mm + limits.edge_clearance_mm
                                     + garment_radius_mm(p, eta), "#d62728", "centre")):
            region = poly.buffer(-inset)
            for ring in _rings(region):
                pts = " ".join(f"{_f(x)},{_f(-y)}" for x, y in ring)
                out.append(f'<polygon points="{pts}" fill="none" stroke="{colour}" '
                           f'stroke-width="0.8" stroke-dasharray="3 2" pointer-events="none" '
                           f'data-guide="{kind}" data-guide-patch="{escape(pid)}"/>')
    return out


def _rings(region) -> list:
    if region.is_empty:
        return []
    polys = getattr(region, "geoms", [region])
    return [np.asarray(r.coords) for poly in polys if poly.geom_type == "Polygon"
            for r in (poly.exterior, *poly.interiors)]


def _open(v: View, background: str = "none") -> str:
    return (f'<svg xmlns="http://www.w3.org/2000/svg" viewBox="{_f(v.x0)} {_f(v.y0)} {_f(v.width)} '
            f'{_f(v.height)}" width="100%" height="100%" style="background:{background}">')


def pieces_layer(design, v: View) -> list[str]:
    """The 50 mm grid and the pieces with their names: what only a zoom, pan or size changes."""
    out = []
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
    return out


def patches_layer(design, heights: dict, eta: float, selected=None, status=None, hoopings=(),
                  also_selected=(), dragging=(), limits=None) -> list[str]:
    """The patches (footprints filled by height, ids, selection and check status), the edge
    rule of dragged patches and the hoopings: what an edit changes."""
    status = status or {}
    out = []
    known = [abs(h) for h in heights.values() if h is not None]
    hmax = max(known + [1.0])
    fills = _height_colours([heights.get(p.id) for p in design.patches], hmax)
    for p, fill in zip(design.patches, fills):
        r = p.diameter_mm / (2.0 * eta)
        x, y = p.centre_mm
        stroke = STATUS_STROKE.get(status.get(p.id), "#333")
        chosen = p.id == selected or p.id in also_selected
        width = 3 if chosen else (2 if p.id in status else 0.8)
        dash = ' stroke-dasharray="4 2"' if chosen else ""
        out.append(f'<circle data-patch="{escape(p.id)}" cx="{_f(x)}" cy="{_f(-y)}" r="{_f(r)}" '
                   f'fill="{fill}" fill-opacity="0.85" '
                   f'stroke="{stroke}" stroke-width="{width}"{dash}/>')
        out.append(f'<text x="{_f(x)}" y="{_f(-y + 3)}" font-size="9" text-anchor="middle" '
                   f'pointer-events="none">{escape(p.id)}</text>')
    if dragging:
        out += guides(design, dragging, eta, limits)
    for corners, label in hoopings:
        pts = " ".join(f"{_f(x)},{_f(-y)}" for x, y in corners)
        out.append(f'<polygon points="{pts}" fill="none" stroke="#1f77b4" stroke-width="1.2" '
                   'stroke-dasharray="6 3" pointer-events="none"/>')
        out.append(f'<text x="{_f(corners[0][0] + 3)}" y="{_f(-corners[0][1] - 3)}" font-size="10" '
                   f'fill="#1f77b4" pointer-events="none">{escape(label)}</text>')
    return out


def svg(design, heights: dict, eta: float, selected: str | None = None, status: dict | None = None,
        hoopings=(), view: View | None = None, also_selected=(), dragging=(), limits=None) -> str:
    """The canvas of ``design`` as one SVG; ``heights``: {patch id: h mm or None}; ``status``:
    {patch id: "error" | "warning"}; ``hoopings``: ((hoop rectangle corners (4, 2) garment mm,
    label), ...); ``view``: the zoomed and panned view (default: fit the pieces);
    ``also_selected``: the rest of a multiple selection; ``dragging``: patches being dragged,
    whose piece-edge rule is drawn (``guides``) with ``limits`` (``CheckLimits``)."""
    v = view or view_of(design)
    return "".join([_open(v, BACKGROUND), *pieces_layer(design, v),
                    *patches_layer(design, heights, eta, selected, status, hoopings,
                                   also_selected, dragging, limits),
                    *rulers(v), "</svg>"])


def layers(design, heights: dict, eta: float, selected: str | None = None,
           status: dict | None = None, hoopings=(), view: View | None = None, also_selected=(),
           dragging=(), limits=None) -> tuple[str, str, str]:
    """The canvas of ``svg`` as three SVGs with the same viewBox, drawn one over the other:
    (pieces, patches, rulers). The page replaces an SVG's markup whole when it changes, and an
    edit changes only the patches: the grid, pieces and rulers stay in the page until the view
    or the size changes."""
    v = view or view_of(design)
    return ("".join([_open(v, BACKGROUND), *pieces_layer(design, v), "</svg>"]),
            patches_svg(design, heights, eta, selected, status, hoopings, v, also_selected,
                        dragging, limits),
            "".join([_open(v), *rulers(v), "</svg>"]))


def patches_svg(design, heights: dict, eta: float, selected: str | None = None,
                status: dict | None = None, hoopings=(), view: View | None = None,
                also_selected=(), dragging=(), limits=None) -> str:
    """The patches' layer of ``layers`` alone: what a drag redraws."""
    v = view or view_of(design)
    return "".join([_open(v), *patches_layer(design, heights, eta, selected, status, hoopings,
                                             also_selected, dragging, limits), "</svg>"])
