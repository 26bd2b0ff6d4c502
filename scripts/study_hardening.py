"""How much of the predictions rests on the hardening term and on its quadratic continuation
past the cutoff (1 - CUTOFF) gamma (docs/model.md, "Compression as physics", where this stands):

1. over the shipped design map, the largest eps_theta / gamma and the designs with a node past
   the cutoff;
2. at the paper's 25 calibration designs, the share of the hardening energy that comes from
   the continuation, and how far h moves when the limit gamma is raised tenfold (3 -> 30 mm).

Usage: python scripts/study_hardening.py
"""
from __future__ import annotations

import numpy as np

from stitchswitch import DEFAULT_MATERIAL, Patch, solve
from stitchswitch.reduced.calibration.designs import CALIBRATION_DESIGNS
from stitchswitch.reduced.design_space.cache import default_map
from stitchswitch.reduced.model.discretization import make_grid
from stitchswitch.reduced.model.terms.hardening import CUTOFF, h


def main() -> None:
    dmap = default_map()
    ratio = np.zeros(dmap.shape)
    past = np.zeros(dmap.shape, dtype=int)
    for i, d in enumerate(dmap.diameter_mm):
        for j, p in enumerate(dmap.fill):
            grid = make_grid(Patch(float(d), float(p)), dmap.material)
            R = np.arange(grid.n_nodes, dtype=float)
            r = R + dmap.u_mm[i, j].astype(float) / grid.dr_mm          # dR units
            eps = r[1:] - grid.lam * R[1:]
            ratio[i, j] = np.max(eps / grid.gamma)
            past[i, j] = int(np.sum(eps > (1.0 - CUTOFF) * grid.gamma))
    i, j = np.unravel_index(np.argmax(ratio), ratio.shape)
    print(f"largest eps_theta / gamma over the map: {ratio.max():.2f} "
          f"(d {dmap.diameter_mm[i]:g} mm, p {dmap.fill[j]:g})")
    print(f"designs with a node past {1 - CUTOFF:g} gamma: {int(np.sum(past > 0))} of {past.size}")
    for limit in (0.5, 0.9, 1.0):
        print(f"designs with eps_theta / gamma above {limit:g}: {int(np.sum(ratio > limit))}")

    shares, moves = [], []
    for d, p in CALIBRATION_DESIGNS:
        sol = solve(Patch(d, p), DEFAULT_MATERIAL)
        grid = make_grid(Patch(d, p), DEFAULT_MATERIAL)
        eps = sol.r_mm[1:] / grid.dr_mm - grid.lam * np.arange(1, grid.n_nodes)
        es = (1.0 - CUTOFF) * grid.gamma
        total = np.sum(h(eps, grid.gamma)[0])
        below = np.sum(h(np.minimum(eps, es), grid.gamma)[0])
        shares.append((total - below) / total if total > 0 else 0.0)
        far = solve(Patch(d, p), DEFAULT_MATERIAL.replace(gamma_mm=10 * DEFAULT_MATERIAL.gamma_mm))
        moves.append(far.keypoints.h_mm - sol.keypoints.h_mm)
    shares, moves = np.array(shares), np.array(moves)
    print(f"calibration designs: share of the hardening energy past the cutoff: median "
          f"{np.median(shares):.1%}, max {shares.max():.1%}, nonzero at {int(np.sum(shares > 0))} of 25")
    print(f"calibration designs: h with gamma x 10 minus h: median {np.median(moves):+.2f} mm, "
          f"max {moves.max():+.2f} mm, min {moves.min():+.2f} mm")


if __name__ == "__main__":
    main()
