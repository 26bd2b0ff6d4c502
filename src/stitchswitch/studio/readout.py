"""The live readout of one patch: keypoints and profile from the design-space map, and the
switching force from the force model.

The map (``reduced.design_space.cache.default_map`` unless another is given) answers in
microseconds by interpolation; it never extrapolates, so a design outside its domain gives a
readout with ``in_domain`` False and a message instead of numbers.
"""
from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache

import numpy as np

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
