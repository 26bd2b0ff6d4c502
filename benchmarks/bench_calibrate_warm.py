"""Measurement: would warm starts speed up calibration's solves without changing its results?

Calibration's objective solves the 25 calibration designs at each material the search tries,
each from the released state (a cold solve). A warm start begins Newton at the solution of the
same design at a nearby material instead. This script draws materials around the default one
in the search coordinates (a normal step of ``s`` times each bound's width, ``s`` from 1 % to
30 %, six materials each, seed 1), solves every design at the search resolution both ways,
and reports the mean Newton iterations of each and how often the warm start ends on another
equilibrium than the cold solve (a keypoint more than 1e-3 mm away), with the largest
difference. Calibration does not use warm starts because of that count (docs/calibration.md,
"Not used: warm starts").

    python benchmarks/bench_calibrate_warm.py [--materials K] [--json]
"""
from __future__ import annotations

import argparse
import json
import sys

import numpy as np

STEPS = (0.01, 0.03, 0.1, 0.2, 0.3)
SAME_MM = 1e-3


def _keypoints(sol) -> np.ndarray:
    kp = sol.keypoints
    return np.array((kp.h_mm, kp.r_a_mm, kp.z_a_mm, kp.r_b_mm, kp.z_b_mm))


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--materials", type=int, default=6, help="materials per step size")
    ap.add_argument("--json", action="store_true")
    args = ap.parse_args(argv)

    from stitchswitch.errors import InvalidInputError
    from stitchswitch.reduced.calibration import evolution as cal
    from stitchswitch.reduced.calibration.designs import CALIBRATION_DESIGNS
    from stitchswitch.reduced.model.params import DEFAULT_MATERIAL, Patch
    from stitchswitch.reduced.solvers.solve import solve

    free = cal.DEFAULT_FREE
    bounds = np.array(cal._search_bounds(free))
    width = bounds[:, 1] - bounds[:, 0]
    base = cal.search_material(DEFAULT_MATERIAL)
    x0 = cal._to_x(base.as_dict(), free)
    sources = [solve(Patch(d, p), base, max_iter=cal.SEARCH_MAX_ITER) for d, p in CALIBRATION_DESIGNS]
    rng = np.random.default_rng(1)
    rows = []
    for s in STEPS:
        cold_it, warm_it, both, other, worst, only_warm = [], [], 0, 0, 0.0, 0
        for _ in range(args.materials):
            x = np.clip(x0 + s * width * rng.standard_normal(len(free)), bounds[:, 0], bounds[:, 1])
            try:
                material = cal._from_x(x, free, base)
            except InvalidInputError:
                continue
            for (d, p), source in zip(CALIBRATION_DESIGNS, sources):
                cold = solve(Patch(d, p), material, max_iter=cal.SEARCH_MAX_ITER)
                warm = solve(Patch(d, p), material, max_iter=cal.SEARCH_MAX_ITER, warm_start=source)
                cold_it.append(cold.iterations)
                warm_it.append(warm.iterations)
                if cold.certified and warm.certified:
                    both += 1
                    diff = float(np.max(np.abs(_keypoints(cold) - _keypoints(warm))))
                    other += diff > SAME_MM
                    worst = max(worst, diff)
                elif warm.certified:
                    only_warm += 1
        rows.append({"step": s, "solves": len(cold_it), "cold_iterations": float(np.mean(cold_it)),
                     "warm_iterations": float(np.mean(warm_it)), "both_certified": both,
                     "other_equilibrium": other, "largest_difference_mm": worst,
                     "only_warm_certified": only_warm})
    if args.json:
        print(json.dumps({"materials_per_step": args.materials, "rows": rows}, indent=1))
        return 0
    print(f"warm against cold starts, {len(CALIBRATION_DESIGNS)} designs at {base.n_nodes} nodes, "
          f"{args.materials} materials per step (step: normal, times each bound's width)")
    print(f"{'step':>5s} {'cold it':>8s} {'warm it':>8s} {'other eq.':>10s} {'largest mm':>11s} "
          f"{'only warm certified':>20s}")
    for r in rows:
        print(f"{r['step']:5.2f} {r['cold_iterations']:8.1f} {r['warm_iterations']:8.1f} "
              f"{r['other_equilibrium']:>4d}/{r['both_certified']:<5d} {r['largest_difference_mm']:11.2f} "
              f"{r['only_warm_certified']:20d}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
