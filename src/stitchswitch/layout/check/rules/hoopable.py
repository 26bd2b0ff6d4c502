"""Rule ``hoopable``: every patch can be hooped where it lies: some hoop of the design (its
``machine.hoop``, else every hoop of its machine), in some orientation, holds the patch's disc
inside its field minus the margin while the hoop's outer rectangle (field plus frame ring) lies
on the fabric, so the frame clamps fabric all round.

The fabric is the stretched piece (outline times eta), grown by the design's
``blank_margin_mm`` times eta when the pieces are hooped as uncut blanks. The search is the
one fabrication runs for a patch no other placement holds (``best_placement``: a 2 mm grid over
every position holding the patch, for every hoop and orientation; ``can_hoop`` walks the same
grid and stops at the first allowed position), and fabrication's candidate
placements are built on the same ``hoop_region``, so ``check`` flags exactly the patches that
``fabricate`` refuses as unhoopable. A patch too large for every hoop is the ``hoop-fit``
rule's, not this one's.
"""
from __future__ import annotations

import numpy as np
import shapely

from stitchswitch.layout.check.rules.hoop import design_hoops
from stitchswitch.layout.check.violation import Violation

RULE = "hoopable"
TOL_MM = 1e-9
STEP_MM = 2.0
#: every how many grid points ``can_hoop`` tries first (a subset's allowed point is the grid's)
COARSE = 4
#: how much (mm) ``core`` is shrunk, so round-off never makes it larger than a rectangle
SHRINK_MM = 1e-6


def hoop_region(outline_mm, blank_mm: float = 0.0):
    """The fabric a hoop frame may clamp: the (stretched) piece outline as a valid polygon,
    grown by ``blank_mm`` when the piece is hooped as an uncut blank; prepared."""
    poly = shapely.Polygon(np.asarray(outline_mm, dtype=float))
    if not poly.is_valid:
        poly = poly.buffer(0)
    if blank_mm > 0:
        poly = poly.buffer(float(blank_mm))
    shapely.prepare(poly)
    return poly


def held(cx, cy, x, y, r, w, h):
    """(len(cx), n) bool: hoop fields of usable size w x h centred at (cx, cy) hold the discs
    (x, y, r)."""
    return ((np.abs(x[None, :] - cx[:, None]) <= w / 2 - r[None, :] + TOL_MM)
            & (np.abs(y[None, :] - cy[:, None]) <= h / 2 - r[None, :] + TOL_MM))


def ring_touches(cx, cy, fw, fh, frame, x, y, r) -> np.ndarray:
    """(len(cx), n) bool: disc i meets the frame ring of width ``frame`` around a field
    fw x fh centred at (cx, cy): it meets the outer rectangle and is not inside the field."""
    dx = np.abs(x[None, :] - cx[:, None])
    dy = np.abs(y[None, :] - cy[:, None])
    ow, oh = fw / 2 + frame, fh / 2 + frame
    ex, ey = np.maximum(dx - ow, 0.0), np.maximum(dy - oh, 0.0)
    meets_outer = ex * ex + ey * ey < (r[None, :] - TOL_MM) ** 2
    inside_field = (dx <= fw / 2 - r[None, :] + TOL_MM) & (dy <= fh / 2 - r[None, :] + TOL_MM)
    return meets_outer & ~inside_field & (frame > 0)


def feasible_box(members, x, y, r, w, h) -> tuple[np.ndarray, ...]:
    """The field centres at which a hoop field of usable size w x h holds every disc of a set:
    the box [lo_x, hi_x] x [lo_y, hi_y], lo_x = max(x + r) - w/2, hi_x = min(x - r) + w/2 over
    the set (likewise y), for each row of ``members`` (bool (s, n) over the discs (x, y, r)) at
    once. Returns (lo_x, hi_x, lo_y, hi_y), each (s,); lo > hi (beyond round-off): no position
    holds the set. The candidate placements of the grouping and the workshop sheet's hoop
    reason both choose positions in it."""
    big = np.where(members, 1.0, np.nan)
    return (np.nanmax(big * (x + r), axis=1) - w / 2, np.nanmin(big * (x - r), axis=1) + w / 2,
            np.nanmax(big * (y + r), axis=1) - h / 2, np.nanmin(big * (y - r), axis=1) + h / 2)


def box_grid(lo_x, hi_x, lo_y, hi_y, n_grid: int):
    """n_grid x n_grid field centres spread evenly over each box of ``feasible_box`` (corners
    included): (cx, cy), each (s, n_grid**2), and the grid's unit coordinates (a, b), each
    (n_grid**2,), x varying fastest."""
    t = np.linspace(0.0, 1.0, n_grid)
    a, b = (g.ravel() for g in np.meshgrid(t, t))
    cx = lo_x[:, None] + a[None, :] * (hi_x - lo_x)[:, None]
    cy = lo_y[:, None] + b[None, :] * (hi_y - lo_y)[:, None]
    return cx, cy, a, b


def allowed(region, cx, cy, ow, oh) -> np.ndarray:
    """(len(cx),) bool: the outer rectangles ow x oh centred at (cx, cy) lie on ``region``."""
    boxes = shapely.box(cx - ow / 2, cy - oh / 2, cx + ow / 2, cy + oh / 2)
    return np.asarray(shapely.contains(region, boxes), dtype=bool)


def _centres(i, x, y, r, hoops, step_mm):
    """Per hoop and orientation that can hold disc i: (k, hoop, o, w, h, cx, cy), the field
    centres holding it on a ``step_mm`` grid as 2D arrays (rows along y)."""
    for k, hoop in enumerate(hoops):
        for o in hoop.orientations:
            w, h = hoop.usable_mm(o)
            if 2 * r[i] > min(w, h) + TOL_MM:
                continue
            sx, sy = w / 2 - r[i], h / 2 - r[i]
            gx = np.linspace(x[i] - sx, x[i] + sx, max(2, int(np.ceil(2 * sx / step_mm)) + 1))
            gy = np.linspace(y[i] - sy, y[i] + sy, max(2, int(np.ceil(2 * sy / step_mm)) + 1))
            cx, cy = np.meshgrid(gx, gy)
            yield k, hoop, o, w, h, cx, cy


def core(x: float, y: float, r: float, w: float, h: float, ow: float, oh: float):
    """The rectangle every outer rectangle ow x oh of ``grid`` for a disc (x, y, r) and a usable
    field w x h contains (minus ``SHRINK_MM``): the field centres span x +- (w/2 - r), so the
    rectangles all cover x +- (ow/2 - w/2 + r), likewise in y. Where it is not on the fabric,
    no outer rectangle is."""
    hx, hy = ow / 2 - w / 2 + r - SHRINK_MM, oh / 2 - h / 2 + r - SHRINK_MM
    return shapely.box(x - hx, y - hy, x + hx, y + hy)


def _core_on(region, i, x, y, r, w, h, ow, oh) -> bool:
    return bool(shapely.contains(region, core(float(x[i]), float(y[i]), float(r[i]),
                                              w, h, ow, oh)))


def grid(i, x, y, r, hoops, region, step_mm):
    """Per hoop and orientation that can hold disc i: (k, o, w, h, cx, cy, allowed mask) over
    the 2 mm grid of field centres holding it (all False, unsearched, where ``core`` is off
    the fabric)."""
    for k, hoop, o, w, h, cx, cy in _centres(i, x, y, r, hoops, step_mm):
        cx, cy = cx.ravel(), cy.ravel()
        ow, oh = hoop.outer_mm(o)
        on = _core_on(region, i, x, y, r, w, h, ow, oh)
        yield k, hoop, o, w, h, cx, cy, (allowed(region, cx, cy, ow, oh) if on
                                         else np.zeros(len(cx), dtype=bool))


def can_hoop(i, x, y, r, hoops, region, step_mm: float = STEP_MM) -> bool:
    """Whether ``best_placement`` finds a placement: the same grid, stopping at the first hoop
    with an allowed point. Per hoop and orientation, a ``core`` off the fabric skips the grid,
    and every ``COARSE``-th point in both directions is tried before the rest; neither changes
    the answer (a subset's point is the grid's; ``core``)."""
    for _k, hoop, o, w, h, cx, cy in _centres(i, x, y, r, hoops, step_mm):
        ow, oh = hoop.outer_mm(o)
        if not _core_on(region, i, x, y, r, w, h, ow, oh):
            continue
        coarse = cx[::COARSE, ::COARSE].ravel(), cy[::COARSE, ::COARSE].ravel()
        if allowed(region, *coarse, ow, oh).any() or allowed(
                region, cx.ravel(), cy.ravel(), ow, oh).any():
            return True
    return False


def best_placement(i, x, y, r, hoops, region, step_mm: float = STEP_MM):
    """The allowed placement holding disc i and the most others: (hoop index, orientation,
    (cx, cy)), or None when no hoop can hold disc i on ``region``."""
    best = None
    for k, hoop, o, w, h, cx, cy, ok in grid(i, x, y, r, hoops, region, step_mm):
        if not ok.any():
            continue
        cx, cy = cx[ok], cy[ok]
        got = held(cx, cy, x, y, r, w, h)
        j = int(np.argmax(got.sum(axis=1)))
        score = (int(got[j].sum()), -hoop.area_mm2)
        if best is None or score > best[0]:
            best = (score, k, o, (float(cx[j]), float(cy[j])))
    return None if best is None else best[1:]


def _fits_some_hoop(r: float, hoops) -> bool:
    return any(2 * r <= min(h.usable_mm(o)) + TOL_MM for h in hoops for o in h.orientations)


def regions(design, eta) -> dict:
    """Per piece name: the fabric its hoop frames may clamp (``hoop_region``, stretched)."""
    blank = design.blank_margin_mm
    return {p.name: hoop_region(np.asarray(p.outline_mm) * eta, blank * eta)
            for p in design.pieces}


def check(design, limits, eta) -> list[Violation]:
    hoops = design_hoops(design)
    blank = design.blank_margin_mm
    regions_ = regions(design, eta)
    out = []
    for patch in design.patches:
        x = np.array([patch.centre_mm[0] * eta])
        y = np.array([patch.centre_mm[1] * eta])
        r = np.array([patch.diameter_mm / 2.0])
        if not _fits_some_hoop(float(r[0]), hoops):
            continue                                  # the hoop-fit rule reports it
        if can_hoop(0, x, y, r, hoops, regions_[patch.piece]):
            continue
        frame = max(h.frame_width_mm for h in hoops)
        hint = (f"move the patch inward, hoop the piece as an uncut blank (blank_margin_mm in "
                f"the design file, or fabricate --blank-margin MM; now {blank:g} mm), or use "
                "fabricate --mode free")
        out.append(Violation(
            RULE, "error", (patch.id,), (patch.piece,), float("nan"), frame,
            f"patch {patch.id} cannot be hooped on piece {patch.piece}: no hoop field (minus "
            f"its margin) holds it with the hoop's frame ring (up to {frame:g} mm) on the "
            f"fabric all round", hint))
    return out
