"""How much of the shipped design map rests on the quadratic continuation of the hardening term
(docs/model.md, "Compression as physics", where this stands): the largest eps_theta / gamma over
the map and the number of designs with a node past the cutoff (1 - CUTOFF) gamma.

Usage: python scripts/study_hardening.py
"""
from __future__ import annotations

import numpy as np

from stitchswitch import Patch
from stitchswitch.reduced.design_space.cache import default_map
from stitchswitch.reduced.model.discretization import make_grid
from stitchswitch.reduced.model.terms.hardening import CUTOFF


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


if __name__ == "__main__":
    main()
