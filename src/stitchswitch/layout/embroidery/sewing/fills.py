"""Filling one convex piece with needle penetrations: tatami or satin, with underlay.

* tatami: horizontal rows ``row_spacing_mm`` apart, sewn back and forth; along a row the needle
  penetrates at most ``max_stitch_mm`` apart on a grid shifted by a third of a stitch from row
  to row (the staggered tatami texture); no stitch shorter than ``min_stitch_mm`` inside a row;
* satin for narrow pieces (x extent at most ``satin_max_width_mm``): a zigzag from edge to edge,
  one stitch per half row spacing;
* pull compensation: every row (tatami and satin) is lengthened by ``extend_mm`` at both ends,
  because the thread tension pulls a knit in across the stitch direction (docs/embroidery.md);
* underlay, sewn first and covered by the top stitches: a *centre walk* up the middle of a satin
  piece, a *tatami underlay* (rows at right angles, ``UNDERLAY_ROW_MM`` apart) in a piece whose
  inscribed circle is at least ``TATAMI_UNDERLAY_INRADIUS_MM``, an *edge run* inset by
  ``underlay_inset_mm`` in the tatami pieces between; a piece too small for its kind gets none.
"""
from __future__ import annotations

import math

import numpy as np

from stitchswitch.layout.embroidery.planar import length

#: a tatami piece at least this "thick" (inscribed radius) gets a tatami underlay
TATAMI_UNDERLAY_INRADIUS_MM = 2.0
#: the tatami underlay's row spacing and stitch length
UNDERLAY_ROW_MM = 1.5
UNDERLAY_STITCH_MM = 2.5
#: a satin piece shorter than this (y extent) gets no centre walk
CENTRE_WALK_MIN_MM = 1.5


def _row_interval(poly: np.ndarray, y: float) -> tuple[float, float] | None:
    xs = []
    for (x0, y0), (x1, y1) in zip(poly, np.roll(poly, -1, axis=0)):
        if (y0 <= y <= y1) or (y1 <= y <= y0):
            if y1 == y0:
                xs += [x0, x1]
            else:
                xs.append(x0 + (y - y0) * (x1 - x0) / (y1 - y0))
    if not xs:
        return None
    return min(xs), max(xs)


def _rows(poly: np.ndarray, spacing: float, extend_mm: float = 0.0):
    """(y, x_left, x_right) of the rows at most ``spacing`` apart, each centred in its band
    (the rows of a convex piece, all edges intersected at once)."""
    ymin, ymax = poly[:, 1].min(), poly[:, 1].max()
    n = max(1, int(math.ceil((ymax - ymin) / spacing - 1e-9)))
    y = ymin + (ymax - ymin) * (np.arange(n) + 0.5) / n
    a, b = poly, np.roll(poly, -1, axis=0)
    lo, hi = np.minimum(a[:, 1], b[:, 1]), np.maximum(a[:, 1], b[:, 1])
    hit = (y[:, None] >= lo[None, :]) & (y[:, None] <= hi[None, :]) & (hi > lo)[None, :]
    dy = np.where(hi > lo, b[:, 1] - a[:, 1], 1.0)
    x = a[None, :, 0] + (y[:, None] - a[None, :, 1]) * ((b[:, 0] - a[:, 0]) / dy)[None, :]
    left = np.where(hit, x, np.inf).min(axis=1)
    right = np.where(hit, x, -np.inf).max(axis=1)
    ok = np.isfinite(left)
    return [(float(yy), float(xl) - extend_mm, float(xr) + extend_mm)
            for yy, xl, xr in zip(y[ok], left[ok], right[ok])]


def tatami(poly: np.ndarray, spacing: float, max_stitch: float, min_stitch: float,
           extend_mm: float = 0.0) -> list[tuple[float, float]]:
    pts = []
    L = max_stitch
    for k, (y, xl, xr) in enumerate(_rows(poly, spacing, extend_mm)):
        phase = (k % 3) / 3.0
        m0 = math.ceil((xl + min_stitch) / L - phase)
        grid = [(m + phase) * L for m in range(m0, m0 + int((xr - xl) / L) + 2)]
        inner = [x for x in grid if xl + min_stitch <= x <= xr - min_stitch]
        row = [xl] + inner + [xr]
        full = [row[0]]
        for x in row[1:]:
            n = max(1, int(math.ceil((x - full[-1]) / L - 1e-9)))
            full += [full[-1] + (x - full[-1]) * (i + 1) / n for i in range(n)]
        if k % 2:
            full = full[::-1]
        pts += [(x, y) for x in full]
    return pts


def satin(poly: np.ndarray, spacing: float, extend_mm: float = 0.0) -> list[tuple[float, float]]:
    pts = []
    for k, (y, xl, xr) in enumerate(_rows(poly, spacing / 2, extend_mm)):
        pts.append((xl, y) if k % 2 == 0 else (xr, y))
    return pts


def _inset(poly: np.ndarray, inset_mm: float) -> np.ndarray | None:
    """The piece shrunk about its centroid so that its edges move in by about ``inset_mm``;
    None when that leaves less than a fifth of it."""
    c = poly.mean(axis=0)
    e = np.roll(poly, -1, axis=0) - poly
    n = np.column_stack([e[:, 1], -e[:, 0]]) / np.linalg.norm(e, axis=1)[:, None]
    inradius = float(np.min(np.abs(np.einsum("ij,ij->i", c - poly, n))))
    f = 1.0 - inset_mm / inradius if inradius > 0 else 0.0
    return None if f <= 0.2 else c + f * (poly - c)


def inradius_mm(poly: np.ndarray) -> float:
    """Distance from the centroid to the nearest edge (the inscribed radius of a triangle)."""
    c = poly.mean(axis=0)
    e = np.roll(poly, -1, axis=0) - poly
    n = np.column_stack([e[:, 1], -e[:, 0]]) / np.linalg.norm(e, axis=1)[:, None]
    return float(np.min(np.abs(np.einsum("ij,ij->i", c - poly, n))))


def edge_run(poly: np.ndarray, inset_mm: float, max_stitch: float) -> list[tuple[float, float]]:
    ring = _inset(poly, inset_mm)
    if ring is None:
        return []
    pts = []
    for a, b in zip(ring, np.roll(ring, -1, axis=0)):
        n_seg = max(1, int(math.ceil(length(b - a) / max_stitch)))
        pts += [tuple(a + (b - a) * i / n_seg) for i in range(n_seg)]
    pts.append(tuple(ring[0]))
    return pts


def tatami_underlay(poly: np.ndarray, inset_mm: float, min_stitch: float) -> list[tuple[float, float]]:
    """Sparse rows at right angles to the top rows, inside the inset piece."""
    ring = _inset(poly, inset_mm)
    if ring is None:
        return []
    turned = ring[:, ::-1] * [1.0, -1.0]             # rotate by -90 degrees: x' = y, y' = -x
    pts = tatami(turned[::-1], UNDERLAY_ROW_MM, UNDERLAY_STITCH_MM, min_stitch)
    return [(-y, x) for x, y in pts]                  # and back


def centre_walk(poly: np.ndarray, inset_mm: float, max_stitch: float) -> list[tuple[float, float]]:
    """A running stitch up the middle of the rows, from the lowest to the highest inset row."""
    ymin, ymax = poly[:, 1].min() + inset_mm, poly[:, 1].max() - inset_mm
    if ymax - ymin < CENTRE_WALK_MIN_MM - 2 * inset_mm:
        return []
    n = max(1, int(math.ceil((ymax - ymin) / max_stitch)))
    pts = []
    for k in range(n + 1):
        y = ymin + (ymax - ymin) * k / n
        iv = _row_interval(poly, y)
        if iv is not None:
            pts.append((0.5 * (iv[0] + iv[1]), y))
    return pts


def fill_piece(poly: np.ndarray, prm, flip_x: bool = False, flip_y: bool = False,
               extend_mm: float | None = None) -> np.ndarray:
    """Needle penetrations filling one convex piece (underlay first); the flips choose the
    starting corner. ``extend_mm``: the pull compensation of this piece (default the
    parameters')."""
    ext = prm.pull_compensation_mm if extend_mm is None else extend_mm
    p = np.asarray(poly, dtype=float).copy()
    sx, sy = (-1.0 if flip_x else 1.0), (-1.0 if flip_y else 1.0)
    q = p * [sx, sy]
    if sx * sy < 0:
        q = q[::-1]                     # keep counter-clockwise after a reflection
    width = q[:, 0].max() - q[:, 0].min()
    is_satin = width <= prm.satin_max_width_mm
    if is_satin:
        body = satin(q, prm.row_spacing_mm, ext)
    else:
        body = tatami(q, prm.row_spacing_mm, prm.max_stitch_mm, prm.min_stitch_mm, ext)
    if not body:
        body = [tuple(q.mean(axis=0))]
    pts = body
    if prm.underlay:
        if is_satin:
            walk = centre_walk(q, prm.underlay_inset_mm, prm.max_stitch_mm)
            if walk:
                pts = walk + body[::-1]      # up the middle, then the zigzag back down
        else:
            if inradius_mm(q) >= TATAMI_UNDERLAY_INRADIUS_MM:
                under = tatami_underlay(q, prm.underlay_inset_mm, prm.min_stitch_mm)
            else:
                under = edge_run(q, prm.underlay_inset_mm, prm.max_stitch_mm)
                if under:
                    start = np.asarray(body[0])
                    k = int(np.argmin(np.linalg.norm(np.asarray(under[:-1]) - start, axis=1)))
                    ring = under[:-1]
                    under = ring[k:] + ring[:k] + [ring[k]]
            pts = under + body
    return np.asarray(pts) * [sx, sy]
