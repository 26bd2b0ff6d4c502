"""Why a hooping uses its hoop, in one sentence for the workshop sheet.

The grouping (``grouping.garment``, ``grouping.free``) chooses hoops for the whole design at
once: fewest frame conflicts, fewest hoopings, fewest hoop types, and only then smaller hoops.
So a single small patch can end up in a long hoop, and the sheet must say why. For one
hooping, ``hoop_reason`` tries every hoop of the machine smaller (by field area) than the one
used, in both turns, on the patches the hooping stitches (their discs on the stretched
fabric):

* none holds them together inside its field minus the margin: the hoop is the smallest that
  does (the patches' span is stated);
* one holds them but, in garment mode, no position of it on a 5 x 5 grid over the positions
  that hold them (``check.rules.hoopable.feasible_box`` and ``box_grid``, the grouping's first
  grid) has its frame on the fabric (``check.rules.hoopable.allowed``, the grouping's own
  test): a smaller hoop does not fit there on the piece;
* otherwise the smaller hoop would do, and the reason is the design-wide objective: one hoop
  type fewer to set up (the grouping prefers that to a smaller hoop) or a frame kept off other
  patches.
"""
from __future__ import annotations

import numpy as np

from stitchswitch.layout.check.rules import hoopable
from stitchswitch.layout.fabrication.grouping.candidates import GRIDS

__all__ = ["hoop_reason"]


def _span(hooping, feet_by_id) -> tuple[np.ndarray, np.ndarray]:
    """Patch centres (piece or hoop coordinates) and radii of the hooping's patches."""
    fs = [feet_by_id[i] for i in hooping.patch_ids]
    if hooping.piece is not None:
        xy = np.array([f.centre_mm for f in fs], dtype=float)
    else:
        xy = np.asarray(hooping.positions_mm, dtype=float)
    return xy, np.array([f.radius_mm for f in fs], dtype=float)


def _placeable(hoop, o, xy, r, region) -> bool:
    """Whether hoop ``hoop`` turned by ``o`` holds the discs, and (with a ``region``) some
    position holding them has its frame on the fabric."""
    w, h = hoop.usable_mm(o)
    box = hoopable.feasible_box(np.ones((1, len(r)), dtype=bool), xy[:, 0], xy[:, 1], r, w, h)
    lo_x, hi_x, lo_y, hi_y = box
    if lo_x[0] > hi_x[0] + hoopable.TOL_MM or lo_y[0] > hi_y[0] + hoopable.TOL_MM:
        return False
    if region is None:
        return True
    cx, cy, _, _ = hoopable.box_grid(*box, GRIDS[0])
    ow, oh = hoop.outer_mm(o)
    return bool(hoopable.allowed(region, cx[0], cy[0], ow, oh).any())


def hoop_reason(hooping, hoops, feet, pieces) -> str:
    """The reason, in plain words, that ``hooping`` uses its hoop (see the module docstring).
    ``hoops``: the hoops the grouping could use; ``feet``/``pieces``: stretched footprints and
    pieces."""
    by_id = {f.id: f for f in feet}
    xy, r = _span(hooping, by_id)
    used = hooping.hoop
    span_w = float(np.max(xy[:, 0] + r) - np.min(xy[:, 0] - r))
    span_h = float(np.max(xy[:, 1] + r) - np.min(xy[:, 1] - r))
    smaller = sorted((h for h in hoops if h.area_mm2 < used.area_mm2 - 1e-9),
                     key=lambda h: h.area_mm2)
    what = (f"patch {hooping.patch_ids[0]}" if len(hooping.patch_ids) == 1
            else f"these {len(hooping.patch_ids)} patches")
    span = f"{what} span{'s' if len(hooping.patch_ids) == 1 else ''} {span_w:.0f} x " \
           f"{span_h:.0f} mm on the stretched fabric"
    holding = [h for h in smaller if any(_placeable(h, o, xy, r, None) for o in h.orientations)]
    if not holding:
        uw, uh = used.usable_mm()
        return (f"{used.name} is the smallest hoop whose field, less its {used.margin_mm:g} mm "
                f"margin ({uw:g} x {uh:g} mm), holds them: {span}")
    region = None
    if hooping.piece is not None:
        piece = next(p for p in pieces if p.name == hooping.piece)
        region = hoopable.hoop_region(piece.outline_mm, piece.blank_mm)
    fitting = [h for h in holding
               if any(_placeable(h, o, xy, r, region) for o in h.orientations)]
    if not fitting:
        names = ", ".join(h.name for h in holding)
        return (f"a smaller hoop ({names}) would hold them ({span}), but its frame would not "
                "lie on the fabric around them there: the frame must clamp fabric all round")
    names = ", ".join(h.name for h in fitting)
    return (f"a smaller hoop ({names}) would also hold them ({span}); {used.name} is used "
            "because the plan as a whole needs fewer hoop types that way (one hoop to set up "
            "instead of two) or keeps this hooping's frame off other patches")
