"""The precomputed design-space map and its real-time queries.

As in the paper (section 5, "we precompute the model across the design space and query it at
runtime"), the map stores the 1D profiles, not meshes: for every grid design (d, p) the
equilibrium of ``solve`` (the same deterministic solve a direct call makes), its keypoints,
energy and certificate, and the profile as radial displacement ``u = r - R`` and height ``z``
(float32, per node).

``DesignMap.query`` interpolates bilinearly in (d, p): keypoints directly, profiles in the
boundary-normalized radius R / R_b (each design has its own node spacing), scaled back to the
queried size. It never extrapolates: a design outside the grid raises ``InvalidInputError``
naming the domain.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from stitchswitch.errors import InvalidInputError
from stitchswitch.reduced.model.params import Material

KEYPOINTS = ("h_mm", "r_a_mm", "z_a_mm", "r_b_mm", "z_b_mm")

#: Codes of ``DesignMap.flags``: how a grid point that fails the neighbour-mean smoothness
#: test is explained (see ``smoothness``).
FLAG_SMOOTH, FLAG_BRANCH, FLAG_ONSET, FLAG_UNRESOLVED, FLAG_UNEXPLAINED = 0, 1, 2, 3, 4
FLAG_NAMES = {FLAG_SMOOTH: "smooth", FLAG_BRANCH: "branch change",
              FLAG_ONSET: "buckling onset", FLAG_UNRESOLVED: "under-resolved",
              FLAG_UNEXPLAINED: "unexplained"}


@dataclass(frozen=True)
class MapQuery:
    """Interpolated keypoints (n,) and, if asked for, profiles (n, N) in mm."""

    diameter_mm: np.ndarray
    fill: np.ndarray
    h_mm: np.ndarray
    r_a_mm: np.ndarray
    z_a_mm: np.ndarray
    r_b_mm: np.ndarray
    z_b_mm: np.ndarray
    R_mm: np.ndarray | None = None
    r_mm: np.ndarray | None = None
    z_mm: np.ndarray | None = None


@dataclass(frozen=True)
class DesignMap:
    diameter_mm: np.ndarray          # (nd,) increasing
    fill: np.ndarray                 # (np,) increasing
    h_mm: np.ndarray                 # (nd, np) ... one array per keypoint
    r_a_mm: np.ndarray
    z_a_mm: np.ndarray
    r_b_mm: np.ndarray
    z_b_mm: np.ndarray
    energy: np.ndarray
    residual: np.ndarray
    converged: np.ndarray            # (nd, np) bool
    u_mm: np.ndarray                 # (nd, np, N) float32, r - R
    z_prof_mm: np.ndarray            # (nd, np, N) float32
    dr_mm: np.ndarray                # (nd,) node spacing of each diameter
    n_inside: np.ndarray             # (nd,) boundary node of each diameter
    material: Material
    material_hash: str
    flags: np.ndarray                # (nd, np) int8, FLAG_* codes
    info: dict = field(default_factory=dict, compare=False)

    @property
    def shape(self) -> tuple[int, int]:
        return self.h_mm.shape

    def domain_text(self) -> str:
        d, p = self.diameter_mm, self.fill
        return f"d in [{d[0]:g}, {d[-1]:g}] mm, fill in [{p[0]:g}, {p[-1]:g}]"

    def _locate(self, grid: np.ndarray, x: np.ndarray, name: str, unit: str):
        bad = ~np.isfinite(x) | (x < grid[0] - 1e-9) | (x > grid[-1] + 1e-9)
        if np.any(bad):
            v = x[np.argmax(bad)]
            raise InvalidInputError(
                f"{name}: {v:g}{unit} is outside the map's domain ({self.domain_text()}); "
                "the map does not extrapolate")
        x = np.clip(x, grid[0], grid[-1])
        i = np.clip(np.searchsorted(grid, x, side="right") - 1, 0, grid.size - 2)
        w = (x - grid[i]) / (grid[i + 1] - grid[i])
        return i, w

    def query(self, diameters, fills, profiles: bool = False) -> MapQuery:
        """Keypoints (and profiles) of arbitrary designs by bilinear interpolation.

        ``diameters`` and ``fills`` broadcast against each other."""
        d, p = np.broadcast_arrays(np.atleast_1d(np.asarray(diameters, dtype=float)),
                                   np.atleast_1d(np.asarray(fills, dtype=float)))
        d, p = d.ravel(), p.ravel()
        i, wd = self._locate(self.diameter_mm, d, "diameter_mm", " mm")
        j, wp = self._locate(self.fill, p, "fill", "")
        corners = ((i, j, (1 - wd) * (1 - wp)), (i + 1, j, wd * (1 - wp)),
                   (i, j + 1, (1 - wd) * wp), (i + 1, j + 1, wd * wp))
        values = {}
        for name in KEYPOINTS:
            table = getattr(self, name)
            values[name] = sum(w * table[a, b] for a, b, w in corners)
        if profiles:
            values.update(self._profiles(d, corners))
        return MapQuery(diameter_mm=d, fill=p, **values)

    def _profiles(self, d: np.ndarray, corners) -> dict:
        from stitchswitch.reduced.model.discretization import n_inside_array

        m = self.material
        n_nodes = self.u_mm.shape[2]
        n_in = n_inside_array(d, m)
        rb = d / (2.0 * m.eta)                                  # rest radius of the boundary
        R = np.arange(n_nodes)[None, :] * (rb / n_in)[:, None]
        s = R / rb[:, None]                                     # boundary-normalized radius
        u = np.zeros_like(R)
        z = np.zeros_like(R)
        for a, b, w in corners:
            # resample each corner's profile at s, in its own node index, normalized by its R_b
            x = s * self.n_inside[a][:, None]
            k = np.minimum(x.astype(int), n_nodes - 2)
            t = np.clip(x - k, 0.0, 1.0)
            rb_c = (self.n_inside[a] * self.dr_mm[a])[:, None]
            for out, table in ((u, self.u_mm), (z, self.z_prof_mm)):
                prof = table[a, b].astype(float)                 # (n, N)
                lo = np.take_along_axis(prof, k, axis=1)
                hi = np.take_along_axis(prof, k + 1, axis=1)
                out += w[:, None] * ((1 - t) * lo + t * hi) / rb_c
        return {"R_mm": R, "r_mm": R + u * rb[:, None], "z_mm": z * rb[:, None]}
