"""Smoothness of a design map, and the explanation of every point that is not smooth.

The test: an interior grid point is smooth if its h lies within 2 % (or 0.05 mm,
whichever is larger) of the mean of its four neighbours. A point that fails is explained as

* ``buckling onset`` if its five-point stencil holds both flat (h < ``FLAT_H_MM``) and
  popped-up designs: the pop-up branch is born there (a bifurcation), and h grows like the
  square root of the distance to it, which no neighbour mean follows;
* ``branch change`` if two distinct certified equilibria coexist across the stencil: the
  design, warm-started from a neighbour's profile (or the neighbour from the design's), settles
  on an equilibrium whose h differs from the map's by more than the test's tolerance; or if,
  failing that, a branch change lies within ``FOLD_STEPS`` designs of it along its row: a branch
  that ends in a fold steepens there (h like the square root of the distance to the fold), which
  no neighbour mean follows;
* ``under-resolved`` if the design is not converged in the discretization: solved again with a
  REFINE times finer spacing (same material), its h moves by more than the test's tolerance.
  This happens for small patches, which the paper's 0.5 mm spacing resolves with only 9-12
  nodes inside; it is not a branch change, and it is reported as what it is;
* ``unexplained`` otherwise: a defect of the map, reported as such.
"""
from __future__ import annotations

import dataclasses
from types import SimpleNamespace

import numpy as np

from stitchswitch.reduced.design_space.design_map import (
    FLAG_BRANCH,
    FLAG_NAMES,
    FLAG_ONSET,
    FLAG_SMOOTH,
    FLAG_UNEXPLAINED,
    FLAG_UNRESOLVED,
    DesignMap,
)
from stitchswitch.reduced.model.keypoints import FLAT_H_MM
from stitchswitch.reduced.model.params import Patch

REL_TOL = 0.02
ABS_TOL_MM = 0.05
REFINE = 4
#: How close (designs along the row) a branch change must be to explain a point next to a fold.
FOLD_STEPS = 2


def violations(h: np.ndarray) -> np.ndarray:
    """Boolean (nd, np): interior points whose h is off the mean of its four neighbours."""
    bad = np.zeros(h.shape, dtype=bool)
    mean = 0.25 * (h[:-2, 1:-1] + h[2:, 1:-1] + h[1:-1, :-2] + h[1:-1, 2:])
    c = h[1:-1, 1:-1]
    bad[1:-1, 1:-1] = np.abs(c - mean) > np.maximum(REL_TOL * np.abs(mean), ABS_TOL_MM)
    return bad


def _profile(dmap: DesignMap, i: int, j: int):
    R = np.arange(dmap.u_mm.shape[2]) * dmap.dr_mm[i]
    return SimpleNamespace(R_mm=R, r_mm=R + dmap.u_mm[i, j], z_mm=dmap.z_prof_mm[i, j].astype(float),
                           n_inside=int(dmap.n_inside[i]), dr_mm=float(dmap.dr_mm[i]))


def _other_equilibrium(dmap: DesignMap, target, source) -> bool:
    """Does ``target`` (i, j), warm-started from ``source``'s profile, settle elsewhere?"""
    from stitchswitch.reduced.solvers.solve import solve

    (i, j), (k, m) = target, source
    sol = solve(Patch(dmap.diameter_mm[i], dmap.fill[j]), dmap.material,
                warm_start=_profile(dmap, k, m))
    if not sol.certified:
        return False
    h = dmap.h_mm[i, j]
    return abs(sol.keypoints.h_mm - h) > max(REL_TOL * abs(h), ABS_TOL_MM)


def _under_resolved(dmap: DesignMap, i: int, j: int) -> bool:
    """Does h move by more than the tolerance when the spacing is REFINE times finer?"""
    from stitchswitch.reduced.solvers.solve import solve

    m = dmap.material
    fine = m.replace(dr_max_mm=m.dr_max_mm / REFINE, n_nodes=m.n_nodes * REFINE)
    h_fine = solve(Patch(dmap.diameter_mm[i], dmap.fill[j]), fine).keypoints.h_mm
    h = dmap.h_mm[i, j]
    return abs(h_fine - h) > max(REL_TOL * abs(h), ABS_TOL_MM)


def classify(dmap: DesignMap) -> DesignMap:
    """Flag every unsmooth point of ``dmap`` with its explanation (``FLAG_*``)."""
    h = dmap.h_mm
    flags = np.full(h.shape, FLAG_SMOOTH, dtype=np.int8)
    for i, j in zip(*np.nonzero(violations(h))):
        stencil = [(i, j), (i - 1, j), (i + 1, j), (i, j - 1), (i, j + 1)]
        flat = [h[a, b] < FLAT_H_MM for a, b in stencil]
        if any(flat) and not all(flat):
            flags[i, j] = FLAG_ONSET
        elif any(_other_equilibrium(dmap, (i, j), q) or _other_equilibrium(dmap, q, (i, j))
                 for q in stencil[1:]):
            flags[i, j] = FLAG_BRANCH
        elif _under_resolved(dmap, i, j):
            flags[i, j] = FLAG_UNRESOLVED
        else:
            flags[i, j] = FLAG_UNEXPLAINED
    for i, j in zip(*np.nonzero(flags == FLAG_UNEXPLAINED)):
        row = flags[i, max(0, j - FOLD_STEPS):j + FOLD_STEPS + 1]
        if np.any(row == FLAG_BRANCH):          # (the first pass found it resolved)
            flags[i, j] = FLAG_BRANCH
    return dataclasses.replace(dmap, flags=flags)


def report(dmap: DesignMap) -> list[dict]:
    """The flagged points: d, fill, h, the neighbour mean and the explanation."""
    h = dmap.h_mm
    out = []
    for i, j in zip(*np.nonzero(dmap.flags != FLAG_SMOOTH)):
        mean = 0.25 * (h[i - 1, j] + h[i + 1, j] + h[i, j - 1] + h[i, j + 1])
        out.append({"d_mm": float(dmap.diameter_mm[i]), "fill": float(dmap.fill[j]),
                    "h_mm": float(h[i, j]), "neighbour_mean_h_mm": float(mean),
                    "kind": FLAG_NAMES[int(dmap.flags[i, j])]})
    return out
