"""Benchmark: the basins of a strong effect's misfit, and whether the truth's is the lowest.

On SYNTHETIC data (``bench_discover.py``'s cases: the same designs, truth and noise draws),
the true effect's model (the five coefficients free, as the workflow fits a candidate) is fitted
to the case's noisy training rows from many starts, on cold solves only (as
``bench_discover.oracle_fit`` fits it: no branch states). The coefficients start at the
starting model's fit to these rows ("calibrated": cold, ``fit.fit`` from the starting
material) or at the starting material's own ("prior", as ``fit.prior_restart`` starts), the
strength at ``FACTORS`` times the true one: each start is first profiled (the coefficients
refitted with the strength held, ``PROFILE_NFEV`` evaluations), then fitted in every parameter
(``FULL_NFEV``). The oracle start (the true parameters) is fitted in every parameter.

For every basin reached: its strength, its training MSE, and its validation gap to the
noise-free truth (MAE of h and r_a on the validation designs). The question it answers: can a
search that minimizes the training misfit be expected to end where the oracle's fit ends?
Where basins with a lower training misfit than the oracle's end farther from the truth, no
such search can (the misfit prefers them), and the oracle's score is a ceiling only an
observer who knows the true parameters reaches. Where the oracle's misfit is lower than every
calibrated start's but reached from the prior ones, the calibrated coefficients hold the
search in the basin where they absorbed the effect. A bistable design whose cold solve jumps
between branches as the parameters move is what makes the misfit this rough.

    python benchmarks/bench_basins.py [--only ID,...] [--json]
"""
from __future__ import annotations

import argparse
import json
import sys
import time

import numpy as np

import bench_discover as bd
import host

#: The default cases: the strong library effects the workflow fits away from their true strength
#: (docs/discovery.md, "fitted against true strengths").
CASES = ("tension_asymmetry-x3", "boundary_transition-x3", "hoop_bending-x3")
#: Start strengths, as multiples of the true one.
FACTORS = (0.5, 0.65, 0.8, 0.9, 1.0, 1.1, 1.25, 1.4, 1.6, 1.8)
PROFILE_NFEV = 8
FULL_NFEV = 25


def landscape(case: dict) -> dict:
    """Every start's fit on ``case`` (a ``bench_discover`` case with a library source)."""
    from stitchswitch.validation.discovery.evaluate import Evaluator
    from stitchswitch.validation.discovery.fit import fit
    from stitchswitch.validation.discovery.space import BASE_FREE, ModelSpec
    from stitchswitch.validation.discovery.synthetic import START_MATERIAL, TRUE_MATERIAL

    designs, split, kp, clean = bd.dataset(case)
    tr = np.array(split) == "train"
    d_tr = [d for d, t in zip(designs, tr) if t]
    d_va = [d for d, t in zip(designs, tr) if not t]
    ev = Evaluator()                      # cold solves only, as the oracle's fit
    base = ModelSpec(START_MATERIAL, None, BASE_FREE)
    f0 = fit(base, ev, d_tr, kp[tr], base.encode(START_MATERIAL), max_nfev=FULL_NFEV)
    spec = ModelSpec(START_MATERIAL, case["source"], BASE_FREE)
    k = spec.offset
    lo, hi = spec.bounds()
    true = float(case["values"][0])

    def run(label, x0, profile=True):
        c0 = time.process_time()
        x = fit(spec, ev, d_tr, kp[tr], x0, max_nfev=PROFILE_NFEV, free=k).x if profile else x0
        f = fit(spec, ev, d_tr, kp[tr], x, max_nfev=FULL_NFEV)
        gap = np.mean(np.abs(ev.one(spec, f.x, d_va) - clean[~tr]), axis=0)
        return {"start": label, "strength": float(spec.decode(f.x)[1][case["source"]][0]),
                "train_mse_mm2": float(f.mse_mm2), "gap_h_mm": float(gap[0]),
                "gap_r_a_mm": float(gap[1]), "cpu_seconds": time.process_time() - c0}

    starts = []
    for coefficients, xc in (("calibrated", f0.x), ("prior", base.encode(START_MATERIAL))):
        for a in FACTORS:
            values = (a * true,) + tuple(p.probe for p in spec.effect_parameters[1:])
            x0 = np.clip(spec.extend(xc, values), lo, hi)
            starts.append({"coefficients": coefficients, **run(f"{a:g} x true", x0)})
    oracle = {"coefficients": "true", **run("true parameters", spec.encode(
        TRUE_MATERIAL, tuple(case["values"])), profile=False)}
    below = [s for s in starts if s["train_mse_mm2"] < oracle["train_mse_mm2"] - 1e-9]
    best = min(starts, key=lambda s: s["train_mse_mm2"])
    reached = {c: min(s["train_mse_mm2"] for s in starts if s["coefficients"] == c)
               for c in ("calibrated", "prior")}
    return {"id": case["id"], "source": case["source"], "true_strength": true,
            "starting_model_train_mse_mm2": float(f0.mse_mm2), "starts": starts,
            "oracle": oracle, "lowest": best, "lowest_by_coefficients": reached,
            "below_oracle": len(below),
            "below_oracle_farther": sum(s["gap_h_mm"] > oracle["gap_h_mm"] for s in below)}


def print_table(results: list) -> None:
    for r in results:
        print(f"{r['id']}  (true strength {r['true_strength']:.4g}; starting model's training "
              f"MSE {r['starting_model_train_mse_mm2']:.3f} mm^2)")
        print(f"  {'coefficients':12s} {'strength start':16s} {'strength':>10s} {'train MSE':>10s} "
              f"{'gap h':>6s} {'gap r_a':>7s}")
        for s in r["starts"] + [r["oracle"]]:
            print(f"  {s['coefficients']:12s} {s['start']:16s} {s['strength']:10.4g} "
                  f"{s['train_mse_mm2']:10.3f} "
                  f"{s['gap_h_mm']:6.2f} {s['gap_r_a_mm']:7.2f}")
        lo = r["lowest"]
        print(f"  lowest misfit: {lo['strength']:.4g} ({lo['train_mse_mm2']:.3f} mm^2, gap h "
              f"{lo['gap_h_mm']:.2f} mm) against the oracle's {r['oracle']['strength']:.4g} "
              f"({r['oracle']['train_mse_mm2']:.3f} mm^2, gap h {r['oracle']['gap_h_mm']:.2f}); "
              f"{r['below_oracle']} of {len(r['starts'])} starts end below the oracle's misfit, "
              f"{r['below_oracle_farther']} of them farther from the truth (h); lowest misfit "
              f"from the calibrated coefficients {r['lowest_by_coefficients']['calibrated']:.3f}, "
              f"from the prior ones {r['lowest_by_coefficients']['prior']:.3f}\n")


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--only", default=",".join(CASES), help="comma-separated bench_discover "
                    "case ids with a library source")
    ap.add_argument("--json", action="store_true")
    args = ap.parse_args(argv)
    by_id = {c["id"]: c for c in bd.cases()}
    from stitchswitch.validation.discovery.effects import LIBRARY

    ids = [i for i in args.only.split(",") if i]
    bad = [i for i in ids if i not in by_id or by_id[i]["source"] not in LIBRARY]
    if bad:
        print(f"error: --only: {', '.join(bad)} is not a bench_discover case with a library "
              "effect (see bench_discover.py --list)", file=sys.stderr)
        return 2
    results = [landscape(by_id[i]) for i in ids]
    out = {"cases": results, "host": host.record(), "data": "SYNTHETIC"}
    if args.json:
        print(json.dumps(out, indent=2))
    else:
        print_table(results)
        print(f"host: {host.describe(out['host'])}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
