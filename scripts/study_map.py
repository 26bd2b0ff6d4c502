"""The design-space map against direct solves: the measured figures of docs/design-map.md.

Builds the default map three ways on the default grid: the shipped construction (warm sweep
along fill plus cold solves next to every jump), every point cold (``warm_start=False``, what
``solve`` gives), and the warm sweep alone; then reports how the maps agree (energy, h, r_b,
flags), where the sweep alone differs from the direct solves, and which cold solves are not
certified.

    python scripts/study_map.py [--workers N] [--json]
"""
from __future__ import annotations

import argparse
import json
import sys
import time

import numpy as np

from stitchswitch import DEFAULT_MATERIAL
from stitchswitch.executor import run_all
from stitchswitch.reduced.design_space import precompute
from stitchswitch.reduced.design_space.design_map import KEYPOINTS


def _sweep_only(workers: int):
    """The warm sweep without the cold solves next to its jumps (the rows' first pass)."""
    rows = run_all(_sweep_row, [(float(d), precompute.DEFAULT_FILLS.tolist())
                                           for d in precompute.DEFAULT_DIAMETERS_MM], workers, None)
    return np.array(rows)


def _sweep_row(args):
    d, fills = args
    return [s.keypoints.h_mm for s in precompute._sweep(d, fills, DEFAULT_MATERIAL, True)]


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--json", action="store_true")
    args = ap.parse_args(argv)
    t = time.perf_counter()
    warm = precompute.build(workers=args.workers)
    warm_s = time.perf_counter() - t
    t = time.perf_counter()
    cold = precompute.build(workers=args.workers, warm_start=False)
    cold_s = time.perf_counter() - t
    sweep_h = _sweep_only(args.workers)
    d, p = warm.diameter_mm, warm.fill
    same = np.abs(warm.h_mm - cold.h_mm) <= 1e-2
    sweep_off = np.argwhere(np.abs(sweep_h - cold.h_mm) > 1e-2)
    uncertified = np.argwhere(~cold.converged)
    report = {
        "warm_build_s": warm_s, "cold_build_s": cold_s, "points": int(warm.h_mm.size),
        "warm_certified": bool(warm.converged.all()), "warm_max_residual": float(warm.residual.max()),
        "points_on_the_same_equilibrium": int(same.sum()),
        "energy_max_rel_diff": float(np.max(np.abs(warm.energy - cold.energy)[same] / np.abs(cold.energy)[same])),
        "max_abs_diff_mm": {k: float(np.max(np.abs(getattr(warm, k) - getattr(cold, k))[same])) for k in KEYPOINTS},
        "flagged_warm": int((warm.flags != 0).sum()), "flagged_cold": int((cold.flags != 0).sum()),
        "same_flags": bool(np.array_equal(warm.flags != 0, cold.flags != 0)),
        "sweep_alone_differs_at": [(float(d[i]), float(p[j]), float(sweep_h[i, j] - cold.h_mm[i, j]))
                                   for i, j in sweep_off],
        "cold_not_certified": [(float(d[i]), float(p[j]), float(cold.residual[i, j])) for i, j in uncertified],
    }
    if args.json:
        json.dump(report, sys.stdout, indent=1)
        print()
        return 0
    for k, v in report.items():
        print(f"{k:34s} {v}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
