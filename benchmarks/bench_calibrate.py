"""Benchmark: a full calibration on the paper's 25 training samples (target: <= 60 s).

Data: the shipped SYNTHETIC dataset (scripts/make_measured_dataset.py: keypoints of a known
"true" material plus measurement noise). The calibration starts from the default material with
the CLI's defaults (popsize 10, maxiter 30) on local worker processes. Reported: wall time,
train MSE against the noise floor (the true material's MSE on the same noisy rows), the fitted
coefficients next to the true ones (relative to the fixed k_theta_fab, which both share), and
the validation MAE per quantity.

    python benchmarks/bench_calibrate.py [--workers N] [--maxiter K] [--popsize P] [--json]
"""
from __future__ import annotations

import argparse
import json
import pathlib
import sys
import time

import numpy as np

ROOT = pathlib.Path(__file__).resolve().parent.parent


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--maxiter", type=int, default=30)
    ap.add_argument("--popsize", type=int, default=10)
    ap.add_argument("--json", action="store_true")
    args = ap.parse_args(argv)

    from stitchswitch.executor import make_executor
    from stitchswitch.reduced.calibration import evolution as cal
    from stitchswitch.reduced.model.params import DEFAULT_MATERIAL
    from stitchswitch.validation.measured import load_measurements
    from stitchswitch.validation.reference_truth import true_material

    data = load_measurements(ROOT / "src" / "stitchswitch" / "data" / "measured_synthetic.csv")
    train, val = data.split("train"), data.split("val")
    designs = [(r.diameter_mm, r.fill) for r in train]
    measured = data.keypoints("train")
    true = true_material()
    t = time.perf_counter()
    with make_executor(args.workers) as ex:
        result = cal.calibrate(designs, measured, DEFAULT_MATERIAL, maxiter=args.maxiter,
                               popsize=args.popsize, seed=0, executor=ex)
    seconds = time.perf_counter() - t
    true_pred, _ = cal.predict_keypoints(true, designs)
    start_pred, _ = cal.predict_keypoints(DEFAULT_MATERIAL, designs)
    val_pred, _ = cal.predict_keypoints(result.material, [(r.diameter_mm, r.fill) for r in val])
    val_mae = np.mean(np.abs(val_pred - data.keypoints("val")), axis=0)
    out = {
        "n_train": len(train), "workers": args.workers, "maxiter": args.maxiter,
        "popsize": args.popsize, "seconds": seconds, "generations": result.generations,
        "evaluations": result.evaluations,
        "train_mse_start_mm2": float(np.mean((start_pred - measured) ** 2)),
        "train_mse_fitted_mm2": result.mse_mm2,
        "train_mse_true_material_mm2": float(np.mean((true_pred - measured) ** 2)),
        "fitted": {n: getattr(result.material, n) for n in cal.PARAMS},
        "true": {n: getattr(true, n) for n in cal.PARAMS},
        "val_mae_mm": dict(zip(("h", "r_a", "z_a", "r_b", "z_b"), map(float, val_mae))),
        "identifiability": result.identifiability,
        "target_le_60s": seconds <= 60.0,
    }
    if args.json:
        print(json.dumps(out, indent=1))
    else:
        print(f"calibration on {len(train)} samples: {seconds:.0f} s on {args.workers} workers "
              f"(target <= 60 s), {result.generations} generations, {result.evaluations} evaluations")
        print(f"train MSE: start {out['train_mse_start_mm2']:.3f}, fitted {result.mse_mm2:.3f}, "
              f"true material (noise floor) {out['train_mse_true_material_mm2']:.3f} mm^2")
        print(f"{'param':12s} {'fitted':>9s} {'true':>9s}")
        for n in cal.PARAMS:
            print(f"{n:12s} {out['fitted'][n]:9.4g} {out['true'][n]:9.4g}")
        print("val MAE (mm): " + ", ".join(f"{k} {v:.2f}" for k, v in out["val_mae_mm"].items()))
        print(f"  {'PASS' if out['target_le_60s'] else 'FAIL'}  calibration_le_60s")
    return 0 if out["target_le_60s"] else 1


if __name__ == "__main__":
    sys.exit(main())
