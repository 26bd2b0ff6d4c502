"""Circles in a rectangle, placed one at a time at the tightest touching position.

``place`` puts a circle of radius r into a [0, W] x [0, H] container holding circles already:
its candidate centres touch two walls (the corners), a wall and a placed circle, or two placed
circles; of the candidates inside the container and clear of every placed circle it takes the
one whose third-nearest object (wall or circle; the two it touches are the nearest) is closest:
the "maximum hole degree" rule of greedy circle packing, which fills corners and pockets first.
Ties go to the lowest, then leftmost position. ``pack`` places a list in the given order.
Fast and deterministic, not optimal. Spacing s between
circles and no spacing to the walls is obtained by the caller: radii r + s/2 in a container
grown by s/2 on every side.
"""
from __future__ import annotations

from functools import lru_cache

import numpy as np

TOL_MM = 1e-7


@lru_cache(maxsize=256)
def _pairs(k: int):
    return np.triu_indices(k, 1)


def _candidates(r: float, w: float, h: float, centres: np.ndarray, radii: np.ndarray):
    corners = np.array([[r, r], [w - r, r], [r, h - r], [w - r, h - r]])
    if not len(centres):
        return corners
    cx, cy, R = centres[:, 0], centres[:, 1], radii + r
    walls = np.array([r, w - r])[:, None]
    # a vertical wall (x = r or w - r) and a circle; then a horizontal wall and a circle
    dy = np.sqrt(np.maximum(R ** 2 - (walls - cx) ** 2, 0.0))          # (2, k)
    dx = np.sqrt(np.maximum(R ** 2 - (np.array([r, h - r])[:, None] - cy) ** 2, 0.0))
    vx = np.broadcast_to(walls, dy.shape)
    hy = np.broadcast_to(np.array([r, h - r])[:, None], dx.shape)
    parts = [corners,
             np.column_stack([np.concatenate([vx.ravel(), vx.ravel()]),
                              np.concatenate([(cy + dy).ravel(), (cy - dy).ravel()])]),
             np.column_stack([np.concatenate([(cx + dx).ravel(), (cx - dx).ravel()]),
                              np.concatenate([hy.ravel(), hy.ravel()])])]
    i, j = _pairs(len(centres))
    if len(i):
        p, q, ri, rj = centres[i], centres[j], R[i], R[j]
        d = np.hypot(q[:, 0] - p[:, 0], q[:, 1] - p[:, 1])
        ok = (d > 1e-12) & (d <= ri + rj)
        p, q, ri, rj, d = p[ok], q[ok], ri[ok], rj[ok], d[ok]
        a = (ri ** 2 - rj ** 2 + d ** 2) / (2 * d)
        hh = np.sqrt(np.maximum(ri ** 2 - a ** 2, 0.0))
        e = (q - p) / d[:, None]
        m = p + a[:, None] * e
        nrm = np.column_stack([-e[:, 1], e[:, 0]]) * hh[:, None]
        parts += [m + nrm, m - nrm]
    return np.vstack(parts)


def place(r: float, w: float, h: float, centres: np.ndarray, radii: np.ndarray):
    """The tightest free touching position of a circle of radius ``r`` (None if none)."""
    if 2 * r > min(w, h) + TOL_MM:
        return None
    cand = _candidates(r, w, h, centres, radii)
    ok = ((cand[:, 0] >= r - TOL_MM) & (cand[:, 0] <= w - r + TOL_MM)
          & (cand[:, 1] >= r - TOL_MM) & (cand[:, 1] <= h - r + TOL_MM))
    cand = cand[ok]
    gaps = np.column_stack([cand[:, 0] - r, w - r - cand[:, 0], cand[:, 1] - r,
                            h - r - cand[:, 1]])
    if len(centres) and len(cand):
        d = np.hypot(cand[:, None, 0] - centres[None, :, 0], cand[:, None, 1] - centres[None, :, 1])
        d -= radii[None, :] + r
        free = np.all(d >= -TOL_MM, axis=1)
        cand, gaps = cand[free], np.hstack([gaps[free], d[free]])
    if not len(cand):
        return None
    third = np.round(np.maximum(np.partition(gaps, 2, axis=1)[:, 2], 0.0), 6)
    k = np.lexsort((cand[:, 0], np.round(cand[:, 1], 6), third))[0]
    return (float(np.clip(cand[k, 0], r, w - r)), float(np.clip(cand[k, 1], r, h - r)))


def pack(radii, w: float, h: float, placed=None, placed_radii=None):
    """Centres for ``radii`` (in this order) added to the ``placed`` circles, or None if one
    does not fit. Returns an (n, 2) array for the new circles only."""
    centres = np.zeros((0, 2)) if placed is None else np.asarray(placed, dtype=float).reshape(-1, 2)
    rads = np.zeros(0) if placed_radii is None else np.asarray(placed_radii, dtype=float)
    out = []
    for r in radii:
        p = place(float(r), w, h, centres, rads)
        if p is None:
            return None
        out.append(p)
        centres = np.vstack([centres, p])
        rads = np.append(rads, r)
    return np.asarray(out, dtype=float).reshape(-1, 2)
