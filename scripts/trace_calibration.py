"""Convergence traces of calibration's differential evolution on the SYNTHETIC reference dataset
(docs/calibration.md, "Termination": the table there is this script's output).

For each seed the search runs every generation (``--tol 1e-6``, ``--maxiter`` generations) and
records the population's spread after each one (``CalibrationResult.spreads``: the standard
deviation of the members' MSEs over their mean, the measure scipy's termination compares with
``tol``). Reported: the first generation whose spread is at most 20 % (``DE_TOL``) and 15 %, the
evaluations up to it, and two fits, each the search and then the polish at both resolutions
from its best member: "stopped there", the run ``calibrate`` makes with the library's
tolerance (its generations are checked against the trace), and the fit after all
generations. Each with its train MSE, its validation MAE per keypoint and its
identifiability report's condition number and smallest and largest singular values.

The results do not depend on ``--workers`` (tests/test_calibration.py); the traces are
deterministic for a seed.

Usage: python scripts/trace_calibration.py [--seeds 0 1 2] [--popsize 10] [--maxiter 30]
    [--workers 2] [--json]
"""
from __future__ import annotations

import argparse
import json
import pathlib
import sys

import numpy as np

from stitchswitch.executor import make_executor
from stitchswitch.reduced.calibration import evolution as cal
from stitchswitch.reduced.model.params import DEFAULT_MATERIAL
from stitchswitch.validation.measured import load_measurements

DATA = (pathlib.Path(__file__).resolve().parent.parent / "src" / "stitchswitch" / "data"
        / "measured_synthetic.csv")
KEYPOINTS = ("h", "r_a", "z_a", "r_b", "z_b")
TRACE_TOL = 1e-6


def fit_summary(result, val_designs, val_measured) -> dict:
    """Train MSE, validation MAE per keypoint and the identifiability figures of one fit."""
    pred, _ = cal.predict_keypoints(result.material, val_designs)
    mae = np.mean(np.abs(pred - val_measured), axis=0)
    sv = result.identifiability.get("singular_values", [])
    return {"generations": result.generations, "evaluations": result.evaluations,
            "train_mse_mm2": result.mse_mm2,
            "val_mae_mm": dict(zip(KEYPOINTS, map(float, mae))),
            "condition_number": result.identifiability.get("condition_number"),
            "singular_value_min": float(min(sv)) if sv else None,
            "singular_value_max": float(max(sv)) if sv else None}


def first_below(spreads, level: float):
    """The first generation (1-based) whose spread is at most ``level``, or None."""
    return next((g for g, s in enumerate(spreads, 1) if s <= level), None)


def trace_seed(seed: int, popsize: int, maxiter: int, data, executor) -> dict:
    train, val = data.split("train"), data.split("val")
    designs = [(r.diameter_mm, r.fill) for r in train]
    val_designs = [(r.diameter_mm, r.fill) for r in val]
    measured, val_measured = data.keypoints("train"), data.keypoints("val")
    full = cal.calibrate(designs, measured, DEFAULT_MATERIAL, maxiter=maxiter, popsize=popsize,
                         seed=seed, tol=TRACE_TOL, executor=executor)
    stopped = cal.calibrate(designs, measured, DEFAULT_MATERIAL, maxiter=maxiter,
                            popsize=popsize, seed=seed, executor=executor)
    spreads = list(full.spreads)
    g20, g15 = first_below(spreads, cal.DE_TOL), first_below(spreads, 0.15)
    members = popsize * len(cal.DEFAULT_FREE)
    return {"seed": seed, "popsize": popsize, "members": members, "spreads": spreads,
            "first_generation_spread_le_20pct": g20, "first_generation_spread_le_15pct": g15,
            "search_evaluations_to_20pct": None if g20 is None else members * (g20 + 1),
            "stopped_generations_match_trace": stopped.generations == (g20 or maxiter),
            "stopped": fit_summary(stopped, val_designs, val_measured),
            "all_generations": fit_summary(full, val_designs, val_measured)}


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--seeds", type=int, nargs="+", default=[0, 1, 2])
    ap.add_argument("--popsize", type=int, default=10)
    ap.add_argument("--maxiter", type=int, default=30)
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--json", action="store_true")
    args = ap.parse_args(argv)
    data = load_measurements(DATA)
    rows = []
    with make_executor(args.workers) as ex:
        for seed in args.seeds:
            rows.append(trace_seed(seed, args.popsize, args.maxiter, data, ex))
            if not args.json:
                print(f"seed {seed} done", file=sys.stderr)
    if args.json:
        print(json.dumps({"dataset": str(DATA.name), "tol": cal.DE_TOL, "rows": rows}, indent=1))
        return 0
    print(f"popsize {args.popsize}, {args.maxiter} generations, DE_TOL {cal.DE_TOL}")
    print("| seed | spread <= 20 % after generation (search evaluations) | <= 15 % | stopped there: "
          "train MSE | val MAE h / r_a / z_a / r_b / z_b | after all: train MSE | val MAE |")
    for r in rows:
        s, a = r["stopped"], r["all_generations"]
        print(f"| {r['seed']} | {r['first_generation_spread_le_20pct']} "
              f"({r['search_evaluations_to_20pct']}) | {r['first_generation_spread_le_15pct']} "
              f"| {s['train_mse_mm2']:.3f} | {_mae(s)} | {a['train_mse_mm2']:.3f} | {_mae(a)} |")
    print("condition number (singular values min-max): "
          + "; ".join(f"seed {r['seed']}: stopped {_cond(r['stopped'])}, all {_cond(r['all_generations'])}"
                      for r in rows))
    print("spreads by generation:")
    for r in rows:
        print(f"  seed {r['seed']}: " + " ".join(f"{x:.2f}" for x in r["spreads"]))
    bad = [r["seed"] for r in rows if not r["stopped_generations_match_trace"]]
    if bad:
        print(f"the default-tolerance run did not stop where the trace says for seeds {bad}")
    return 1 if bad else 0


def _mae(fit) -> str:
    return " / ".join(f"{fit['val_mae_mm'][k]:.2f}" for k in KEYPOINTS)


def _cond(fit) -> str:
    return (f"{fit['condition_number']:.0f} ({fit['singular_value_min']:.2f}-"
            f"{fit['singular_value_max']:.0f})")


if __name__ == "__main__":
    sys.exit(main())
