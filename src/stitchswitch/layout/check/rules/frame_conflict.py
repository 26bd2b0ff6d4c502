"""Rule ``frame-conflict`` (warning): two patches so placed that whichever is stitched first, the
hoop frame of the other's hooping will press it.

For patches i and j on one piece: no allowed placement (the ``hoopable`` rule's: a hoop of the
design, either turn, field minus margin holding the disc, frame on the fabric) holding i keeps
its frame ring off j, and none holding j keeps its frame off i. No placement then holds both
(one that did would hold j inside its field, off its ring), so i and j are in different
hoopings, and the later one's frame lands on the earlier one: a frame conflict that no
grouping or order avoids (fabrication's plan names which frame and which patch). The
placements are searched on a ``STEP_MM`` grid of field centres (coarser than ``hoopable``'s:
this is a warning, and a free position between grid points is possible).

value: the gap between the two footprints on the stretched fabric; limit: the frame ring
width (25 mm on the 550E), the order of the distance that moving them apart must add.
"""
from __future__ import annotations

import numpy as np

from stitchswitch.layout.check.rules import hoopable
from stitchswitch.layout.check.rules.hoop import design_hoops
from stitchswitch.layout.check.violation import Violation

RULE = "frame-conflict"
STEP_MM = 5.0


def _free_of(i, x, y, r, hoops, region, needed) -> np.ndarray | None:
    """(n,) bool: some allowed placement holding disc i keeps its frame ring off disc j (the
    search stops once that holds for every j of ``needed``); None when no allowed placement
    holds i (the ``hoopable`` rule reports that)."""
    free = np.zeros(len(x), dtype=bool)
    any_allowed = False
    for _k, hoop, o, _w, _h, cx, cy, ok in hoopable.grid(i, x, y, r, hoops, region, STEP_MM):
        if not ok.any():
            continue
        any_allowed = True
        fw, fh = hoop.field_mm(o)
        ring = hoopable.ring_touches(cx[ok], cy[ok], fw, fh, hoop.frame_width_mm, x, y, r)
        free |= ~ring.all(axis=0)
        if free[needed].all():
            break
    return free if any_allowed else None


def check(design, limits, eta) -> list[Violation]:
    hoops = design_hoops(design)
    frame = max(h.frame_width_mm for h in hoops)
    if frame <= 0:
        return []
    regions = hoopable.regions(design, eta)
    reach = max(max(h.outer_mm()) for h in hoops)      # a frame touches nothing farther away
    out = []
    for piece in design.pieces:
        mine = [p for p in design.patches if p.piece == piece.name]
        if len(mine) < 2:
            continue
        x = np.array([p.centre_mm[0] * eta for p in mine])
        y = np.array([p.centre_mm[1] * eta for p in mine])
        r = np.array([p.diameter_mm / 2.0 for p in mine])
        dist = np.hypot(x[:, None] - x[None, :], y[:, None] - y[None, :])
        near = (dist < reach + r[:, None] + r[None, :]) & ~np.eye(len(mine), dtype=bool)
        free = {}
        for i in np.flatnonzero(near.any(axis=1)):
            free[i] = _free_of(i, x, y, r, hoops, regions[piece.name], near[i])
        for i, j in zip(*np.nonzero(np.triu(near))):
            if free.get(i) is None or free.get(j) is None or free[i][j] or free[j][i]:
                continue
            a, b = mine[i], mine[j]
            gap = float(dist[i, j] - r[i] - r[j])
            out.append(Violation(
                RULE, "warning", (a.id, b.id), (piece.name,), gap, frame,
                f"patches {a.id} and {b.id}: every hoop position holding one puts its frame "
                f"on the other and none holds both, so whichever is stitched first will be "
                f"pressed by the frame of the other's hooping",
                f"move them apart (about {frame:g} mm more on the stretched fabric, "
                f"{frame / eta:.0f} mm relaxed) or close enough for one hoop to hold both; "
                "else pad the first one when hooping the second (the fabrication sheet says "
                "which)"))
    return out
