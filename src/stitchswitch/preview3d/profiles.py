"""The equilibrium profile of every patch of a preview.

Profiles come from the design-space map of the material (``reduced.design_space.cache``), as in the
paper's live preview: the shipped map for the default material, or a map already in the cache
for another material. The preview never builds a map (that takes minutes): a design outside the
map's domain, or any design of a material without a cached map, is solved directly
(``reduced.solvers.solve``, a few ms each). Identical designs are looked up once.

Profiles are the model's: ``R_mm`` the rest radius of every node in the relaxed fabric,
``r_mm`` the deformed radius and ``z_mm`` the height (z = 0 at the outermost node), all in mm;
node ``n_inside`` lies on the embroidery boundary, at R = d / (2 eta). The keypoints are computed
from the very profile that is drawn (``reduced.model.keypoints``), so the figure and the numbers agree.
"""
from __future__ import annotations

import logging
from dataclasses import dataclass

import numpy as np

from stitchswitch.reduced.model.keypoints import Keypoints, keypoints_from_profile
from stitchswitch.reduced.model.params import DEFAULT_MATERIAL, Material, Patch

log = logging.getLogger(__name__)


@dataclass(frozen=True, eq=False)
class PatchProfile:
    """Profile of one design (mm); ``source`` is "map" or "solve"."""

    diameter_mm: float
    fill: float
    R_mm: np.ndarray
    r_mm: np.ndarray
    z_mm: np.ndarray
    n_inside: int
    keypoints: Keypoints
    source: str

    @property
    def boundary_radius_mm(self) -> float:
        """Rest radius of the embroidery boundary in the relaxed fabric, d / (2 eta)."""
        return float(self.R_mm[self.n_inside])


def available_map(material: Material):
    """The material's design map if it ships or is cached, else None (never builds one)."""
    from stitchswitch.reduced.design_space import cache

    if material == DEFAULT_MATERIAL:
        return cache.default_map()
    return cache.cached_map(material)


def _in_domain(dmap, d: float, p: float) -> bool:
    return (dmap.diameter_mm[0] <= d <= dmap.diameter_mm[-1]
            and dmap.fill[0] <= p <= dmap.fill[-1])


def _from_map(dmap, designs: list[tuple[float, float]]) -> list[PatchProfile]:
    from stitchswitch.reduced.model.discretization import n_inside_array

    d = np.array([x[0] for x in designs])
    p = np.array([x[1] for x in designs])
    q = dmap.query(d, p, profiles=True)
    n_in = n_inside_array(d, dmap.material)
    out = []
    for k in range(d.size):
        R, r, z = q.R_mm[k], q.r_mm[k], q.z_mm[k] - q.z_mm[k, -1]
        kp = keypoints_from_profile(R, r, z, int(n_in[k]))
        out.append(PatchProfile(float(d[k]), float(p[k]), R, r, z, int(n_in[k]), kp, "map"))
    return out


def _from_solve(d: float, p: float, material: Material) -> PatchProfile:
    from stitchswitch.reduced.solvers.solve import solve

    sol = solve(Patch(d, p), material)
    if not sol.converged:
        log.warning("d = %g mm, fill = %g: the solve did not converge (residual %.2e); "
                    "the preview shows an uncertified profile", d, p, sol.residual)
    return PatchProfile(d, p, np.asarray(sol.R_mm), np.asarray(sol.r_mm), np.asarray(sol.z_mm),
                        sol.n_inside, sol.keypoints, "solve")


def patch_profiles(diameters_mm, fills,
                   material: Material = DEFAULT_MATERIAL) -> list[PatchProfile]:
    """One profile per (diameter, fill) pair, in order."""
    designs = [(float(d), float(p)) for d, p in zip(diameters_mm, fills, strict=True)]
    for d, p in designs:
        Patch(d, p)                                   # validates with the model's messages
    unique = sorted(set(designs))
    dmap = available_map(material)
    from_map = [x for x in unique if dmap is not None and _in_domain(dmap, *x)]
    found = dict(zip(from_map, _from_map(dmap, from_map))) if from_map else {}
    for x in unique:
        if x not in found:
            found[x] = _from_solve(x[0], x[1], material)
    return [found[x] for x in designs]


def single_profile(diameter_mm: float, fill: float,
                   material: Material = DEFAULT_MATERIAL) -> PatchProfile:
    return patch_profiles([diameter_mm], [fill], material)[0]

