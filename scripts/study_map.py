"""The design-space map against direct solves: the measured figures of docs/design-map.md.

Builds the default map two ways on the default grid: the shipped construction (a warm sweep
of each row along increasing fill) and every point cold (``warm_start=False``, what ``solve``
gives); then reports how the maps agree (energy, h, r_b, flags), where the cold solves hold
another equilibrium, and which cold solves are not certified.

    python scripts/study_map.py [--workers N] [--json]

``--perturb`` instead re-solves the rows d = 35-99 mm (the band where the dome and the neck
coexist) with the released state and every warm start scaled by 1 + eps (eps = +-1e-12, 1e-9:
a change of round-off), and counts the points that change branch in the map and among the
cold solves of the same designs.

``--compare OLD.npz NEW.npz`` instead lists where two maps of the same grid hold another
equilibrium (h differs by more than 0.05 mm): the changes of branch a change of the map's
construction or the solver's path makes (docs/design-map.md), with the energy change of each,
and the largest differences elsewhere.
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


def _perturbed_row(args):
    """One row of the map and the cold solves of every design, with the released state and
    every warm start scaled by (1 + eps): the heights (map, cold) under a round-off change."""
    from stitchswitch import Patch, solve
    from stitchswitch.reduced.solvers import continuation
    from stitchswitch.reduced.solvers import solve as solve_module

    d, eps = args
    released, warm = continuation.released_state, solve_module._warm_profile
    continuation.released_state = lambda grid, fraction=continuation.SEED_FRACTION: tuple(
        a * (1 + eps) for a in released(grid, fraction))
    solve_module._warm_profile = lambda start, grid: tuple(a * (1 + eps) for a in warm(start, grid))
    try:
        fills = precompute.DEFAULT_FILLS.tolist()
        row = precompute._solve_row((d, fills, DEFAULT_MATERIAL, True))[0]["h_mm"]
        cold = [solve(Patch(d, p)).keypoints.h_mm for p in fills]
    finally:
        continuation.released_state, solve_module._warm_profile = released, warm
    return row, cold


#: The round-off perturbations of ``--perturb`` (relative scaling of every start).
PERTURBATIONS = (1e-12, -1e-12, 1e-9)


def perturb(workers: int, diameters_mm) -> dict:
    """How many points change branch (h by more than ``BRANCH_MM``) when every start is
    scaled by 1 + eps: in the map (the warm sweep), and among the cold solves."""
    base = np.array(run_all(_perturbed_row, [(float(d), 0.0) for d in diameters_mm], workers, None))
    out = {"rows": len(diameters_mm), "points": int(base[:, 0].size)}
    for eps in PERTURBATIONS:
        rows = np.array(run_all(_perturbed_row, [(float(d), eps) for d in diameters_mm], workers, None))
        moved = np.abs(rows - base) > BRANCH_MM
        out[f"{eps:g}"] = {"map_points_moved": int(moved[:, 0].sum()),
                          "cold_solves_moved": int(moved[:, 1].sum())}
    return out


#: |h| difference (mm) above which two maps hold another equilibrium at a point.
BRANCH_MM = 0.05


def compare(old_path, new_path) -> dict:
    """The points where two maps hold different equilibria, and the largest differences
    elsewhere."""
    from stitchswitch.reduced.design_space.storage import load_map

    old, new = load_map(old_path), load_map(new_path)
    if not (np.array_equal(old.diameter_mm, new.diameter_mm) and np.array_equal(old.fill, new.fill)):
        raise SystemExit("study_map --compare: the two maps have different grids")
    dh = new.h_mm - old.h_mm
    rel_e = (new.energy - old.energy) / np.abs(old.energy)
    moved = np.abs(dh) > BRANCH_MM
    return {
        "points": int(dh.size),
        "changes_of_branch": [
            {"d_mm": float(old.diameter_mm[i]), "fill": float(old.fill[j]),
             "h_old_mm": float(old.h_mm[i, j]), "h_new_mm": float(new.h_mm[i, j]),
             "energy_rel_change": float(rel_e[i, j])} for i, j in np.argwhere(moved)],
        "elsewhere_max_abs_dh_mm": float(np.abs(dh[~moved]).max()),
        "elsewhere_max_energy_rel_change": float(np.abs(rel_e[~moved]).max()),
        "flags_moved": int((old.flags != new.flags).sum()),
        "flagged_old": int((old.flags != 0).sum()), "flagged_new": int((new.flags != 0).sum()),
        "new_all_certified": bool(new.converged.all()),
    }


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--json", action="store_true")
    ap.add_argument("--compare", nargs=2, metavar=("OLD", "NEW"))
    ap.add_argument("--perturb", action="store_true",
                    help="the rows d 35-99 mm with every start perturbed by round-off")
    args = ap.parse_args(argv)
    if args.perturb:
        report = perturb(args.workers, np.arange(35.0, 99.0 + 0.5, 1.0))
        print(json.dumps(report, indent=1) if args.json else
              "\n".join(f"{k:34s} {v}" for k, v in report.items()))
        return 0
    if args.compare:
        report = compare(*args.compare)
        if args.json:
            json.dump(report, sys.stdout, indent=1)
            print()
            return 0
        for k, v in report.items():
            if k == "changes_of_branch":
                print(f"{k}: {len(v)}")
                for c in v:
                    print(f"  d {c['d_mm']:.0f} mm, p {c['fill']:.2f}: h {c['h_old_mm']:.2f} -> "
                          f"{c['h_new_mm']:.2f} mm, energy {c['energy_rel_change']:+.1e} (relative)")
            else:
                print(f"{k:34s} {v}")
        return 0
    t = time.perf_counter()
    warm = precompute.build(workers=args.workers)
    warm_s = time.perf_counter() - t
    t = time.perf_counter()
    cold = precompute.build(workers=args.workers, warm_start=False)
    cold_s = time.perf_counter() - t
    d, p = warm.diameter_mm, warm.fill
    same = np.abs(warm.h_mm - cold.h_mm) <= 1e-2
    uncertified = np.argwhere(~cold.converged)
    report = {
        "warm_build_s": warm_s, "cold_build_s": cold_s, "points": int(warm.h_mm.size),
        "warm_certified": bool(warm.converged.all()), "warm_max_residual": float(warm.residual.max()),
        "points_on_the_same_equilibrium": int(same.sum()),
        "energy_max_rel_diff": float(np.max(np.abs(warm.energy - cold.energy)[same] / np.abs(cold.energy)[same])),
        "max_abs_diff_mm": {k: float(np.max(np.abs(getattr(warm, k) - getattr(cold, k))[same])) for k in KEYPOINTS},
        "flagged_warm": int((warm.flags != 0).sum()), "flagged_cold": int((cold.flags != 0).sum()),
        "same_flags": bool(np.array_equal(warm.flags != 0, cold.flags != 0)),
        "cold_differs_at": [(float(d[i]), float(p[j]), float(warm.h_mm[i, j]), float(cold.h_mm[i, j]),
                             float((cold.energy[i, j] - warm.energy[i, j]) / abs(warm.energy[i, j])))
                            for i, j in np.argwhere(~same)],
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
