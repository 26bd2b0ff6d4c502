"""The live readout of one patch: keypoints and profile from the design-space map, and the
switching force from the force model, and the profile as the inspector's small plot
(``profile_svg``: z(r) as SVG, both axes in mm at the same scale, the flat fabric at z = 0 grey).

The map (``reduced.design_space.cache.default_map`` unless another is given) answers in
microseconds by interpolation; it never extrapolates, so a design outside its domain gives a
readout with ``in_domain`` False and a message instead of numbers.
"""
from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache

import numpy as np
from shapely.geometry import LineString

from stitchswitch.errors import InvalidInputError
from stitchswitch.reduced.design_space.design_map import KEYPOINTS


@dataclass(frozen=True, eq=False)
class Readout:
    diameter_mm: float
    fill: float
    in_domain: bool
    keypoints_mm: dict             # h_mm, r_a_mm, z_a_mm, r_b_mm, z_b_mm
    force_N: float | None
    force_extrapolated: bool | None
    r_mm: np.ndarray | None        # the profile (deformed radius, height), mm
    z_mm: np.ndarray | None
    message: str = ""

    def as_dict(self) -> dict:
        return {"d_mm": self.diameter_mm, "fill": self.fill, "in_domain": self.in_domain,
                **self.keypoints_mm, "force_N": self.force_N,
                "force_extrapolated": self.force_extrapolated, "message": self.message}


@lru_cache(maxsize=1)
def _force():
    from stitchswitch.reduced.design_space.force_model import default_force_fit

    return default_force_fit()


def readout(dmap, diameter_mm: float, fill: float) -> Readout:
    """The readout of design (``diameter_mm``, ``fill``) on ``dmap``."""
    try:
        q = dmap.query(diameter_mm, fill, profiles=True)
    except InvalidInputError as exc:
        return Readout(float(diameter_mm), float(fill), False, {k: None for k in KEYPOINTS},
                       None, None, None, None, str(exc))
    fit = _force()
    force = float(fit.model.predict(diameter_mm, fill))
    return Readout(float(diameter_mm), float(fill), True,
                   {k: float(getattr(q, k)[0]) for k in KEYPOINTS}, force,
                   bool(fit.extrapolates(diameter_mm, fill)), q.r_mm[0], q.z_mm[0])


def heights_mm(dmap, design) -> dict:
    """{patch id: predicted h (mm) or None outside the map} for every patch of ``design`` (one
    query of the map for all patches inside its domain)."""
    d = np.array([p.diameter_mm for p in design.patches], dtype=float)
    f = np.array([p.fill for p in design.patches], dtype=float)
    inside = ((dmap.diameter_mm[0] <= d) & (d <= dmap.diameter_mm[-1])
              & (dmap.fill[0] <= f) & (f <= dmap.fill[-1]))
    h = dmap.query(d[inside], f[inside]).h_mm if inside.any() else np.zeros(0)
    found = iter(h.tolist())
    return {p.id: (next(found) if ok else None) for p, ok in zip(design.patches, inside)}


#: the profile plot's size and its margin
WIDTH_PX, HEIGHT_PX, PAD_MM = 340, 120, 2.0
#: the plotted profile keeps its nodes to within this many pixels of the plot (Douglas-Peucker):
#: the map's 300 nodes a side made the readout's message 7.7 kB, sent and drawn at every slider
#: step, for a line a few hundred pixels long
SIMPLIFY_PX = 0.25


def profile_svg(r_mm, z_mm) -> str:
    """SVG of the profile (r_mm, z_mm) and its mirror image (-r, z); empty without a profile."""
    if r_mm is None or z_mm is None or len(r_mm) < 2:
        return ""
    r, z = np.asarray(r_mm, dtype=float), np.asarray(z_mm, dtype=float)
    x0, x1 = -r.max() - PAD_MM, r.max() + PAD_MM
    y0, y1 = min(z.min(), 0.0) - PAD_MM, max(z.max(), 0.0) + PAD_MM
    mm_per_px = max((x1 - x0) / WIDTH_PX, (y1 - y0) / HEIGHT_PX)      # the viewBox's "meet"
    half = np.asarray(LineString(np.column_stack([r, z])).simplify(SIMPLIFY_PX * mm_per_px).coords)
    x = np.concatenate([-half[::-1, 0], half[:, 0]])
    y = np.concatenate([half[::-1, 1], half[:, 1]])
    pts = " ".join(f"{a:.2f},{-b:.2f}" for a, b in zip(x, y))
    return (f'<svg xmlns="http://www.w3.org/2000/svg" width="{WIDTH_PX}" height="{HEIGHT_PX}" '
            f'viewBox="{x0:.2f} {-y1:.2f} {x1 - x0:.2f} {y1 - y0:.2f}">'
            f'<line x1="{x0:.2f}" y1="0" x2="{x1:.2f}" y2="0" stroke="#bbb" stroke-width="0.4"/>'
            f'<polyline data-profile="1" points="{pts}" fill="none" stroke="#b40426" '
            'stroke-width="0.8"/></svg>')
