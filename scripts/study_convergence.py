"""Observed convergence order of r_a and h in the node count N (docs/model.md, "Boundary
quadrature"): the table there is this script's output.

The domain is held fixed (dR_max = 0.5 mm x 300 / N, so the spacing halves as N doubles); the
order from three refinements is p = log2(|q_N - q_2N| / |q_2N - q_4N|). For each design the
script also reports whether its equilibrium at N = 300 is taut everywhere (no segment shorter
than its rest length), which is where the solution is smooth.

Usage: python scripts/study_convergence.py
"""
from __future__ import annotations

import math

import numpy as np

from stitchswitch import DEFAULT_MATERIAL, Patch, solve
from stitchswitch.reduced.model.discretization import make_grid
from stitchswitch.reduced.model.terms.variants import PAPER_INDEXING

DESIGNS = [(90.0, 1.0), (70.0, 1.0), (60.0, 0.9), (40.0, 0.8), (20.0, 0.6), (90.0, 0.6)]
LEVELS = (150, 300, 600, 1200)


def order(values) -> float:
    a, b, c = values
    if b == c:
        return math.inf
    return math.log2(abs(a - b) / abs(b - c)) if a != b else -math.inf


def min_stretch(sol) -> float:
    grid = make_grid(sol.patch, sol.material)
    return float(np.min(np.hypot(np.diff(sol.r_mm), np.diff(sol.z_mm)) / sol.dr_mm / grid.lam))


def main() -> None:
    print("| design | min stretch at N = 300 | rule | q | " + " | ".join(f"N = {n}" for n in LEVELS)
          + " | order (150-300-600) | order (300-600-1200) |")
    print("|---|---|---|---|" + "---|" * len(LEVELS) + "---|---|")
    for d, p in DESIGNS:
        stretch = min_stretch(solve(Patch(d, p)))
        for rule, terms in (("trapezoid", None), ("paper", PAPER_INDEXING)):
            sols = [solve(Patch(d, p), DEFAULT_MATERIAL.replace(n_nodes=n, dr_max_mm=0.5 * 300 / n),
                          terms=terms) for n in LEVELS]
            for q in ("r_a_mm", "h_mm"):
                v = [getattr(s.keypoints, q) for s in sols]
                flag = "" if all(s.converged for s in sols) else " (not all certified)"
                print(f"| d {d:g}, p {p:g} | {stretch:.3f} | {rule} | {q[:-3]} | "
                      + " | ".join(f"{x:.3f}" for x in v)
                      + f" | {order(v[:3]):.2f} | {order(v[1:]):.2f}{flag} |")


if __name__ == "__main__":
    main()
