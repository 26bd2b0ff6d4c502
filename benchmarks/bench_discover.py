"""Benchmark: discrepancy discovery on SYNTHETIC data with hidden effects.

For every effect of the library, ``--per-effect`` (default 3) datasets with a random strength
from the effect's documented hidden range; ``--null`` datasets without any hidden effect; two
datasets with ``gravity_sag`` (a control effect that is NOT in the library: naming anything is a
false discovery); one dataset from the finite-element shell reference with hoop bending and
Poisson coupling (``--no-fem`` skips it). Each dataset has the paper's 25 train + 28 val designs
and the synthetic reference dataset's noise (``validation.discovery.synthetic``). The workflow
runs with its default settings from the starting material, not told the source.

Reported per case: the source and its strength, the named effect and fitted strength, the
validation MAE (against the noisy rows) before and after, the *gap* before and after (MAE of
the predictions against the noise-free truth on the validation designs: what the model gets
wrong, without the measurement noise no model can remove), time and solves. Two yardsticks
that need no guessing:

* the **noise floor**: the validation MAE of the noise-free truth itself against the noisy
  rows (what the exact true model, with the true parameters, scores). No model can go below
  it, so the largest reduction of the noisy validation MAE that any model can reach is
  1 - floor / before (the *achievable* reduction);
* the **oracle fit**: the true model (the hidden effect) fitted to the same noisy training
  rows by the same least squares, started from the true parameters. Its validation gap is what
  the noise in 25 training rows leaves even when the search starts at the answer.

Summary: identification accuracy over the library cases (target >= 90 %), false discoveries on
null data (target 0) and on the control, median gap reduction of h and r_a, share of library
cases whose h and r_a gaps fall by >= 50 % (and how many of those the oracle halves), the
noisy-row reduction next to the achievable one, runtime per workflow run (target <= 600 s).

    python benchmarks/bench_discover.py [--workers 2] [--per-effect 3] [--null 3] [--no-fem]
        [--no-control] [--scale S] [--only ID,...] [--log cases.jsonl] [--json]

``--scale S`` multiplies the drawn strengths (the same seeds; ids get ``-xS``): with
``--scale 2 --null 0 --no-fem --no-control`` it shows how the noisy-row reduction and its
achievable bound move when the effects dominate the noise.

``--log`` appends one JSON line per finished case and skips cases already in it (resume).
"""
from __future__ import annotations

import argparse
import json
import pathlib
import sys
import time

import numpy as np

QUANT = ("h", "r_a", "z_a", "r_b", "z_b")


def _scaled(name: str, values, scale: float) -> list:
    """``values`` times ``scale``, kept inside 95 % of the effect's fit bounds."""
    from stitchswitch.validation.discovery.effects import get_effect

    if scale == 1.0:
        return list(values)
    params = get_effect(name).parameters
    return [float(f"{min(max(v * scale, 0.95 * p.lower), 0.95 * p.upper):.4g}")
            for v, p in zip(values, params)]


def cases(per_effect: int, n_null: int, fem: bool, scale: float = 1.0, control: bool = True):
    from stitchswitch.validation.discovery.effects import LIBRARY
    from stitchswitch.validation.discovery.synthetic import draw_values

    out, seed = [], 100
    tag = "" if scale == 1.0 else f"-x{scale:g}"
    for name in LIBRARY:
        for k in range(per_effect):
            seed += 1
            values = draw_values(name, np.random.default_rng([seed, 1]))
            out.append({"id": f"{name}-{k + 1}{tag}", "source": name, "seed": seed,
                        "values": _scaled(name, values, scale)})
    for k in range(n_null):
        seed += 1
        out.append({"id": f"null-{k + 1}", "source": None, "seed": seed, "values": []})
    for k in range(2 if control else 0):
        seed += 1
        out.append({"id": f"gravity_sag-{k + 1}", "source": "gravity_sag", "seed": seed,
                    "values": list(draw_values("gravity_sag", np.random.default_rng([seed, 1])))})
    if fem:
        seed += 1
        out.append({"id": "fem_shell-1", "source": "fem_shell", "seed": seed, "values": []})
    return out


def run_case(case: dict, executor) -> dict:
    from stitchswitch.validation.discovery.effects import LIBRARY
    from stitchswitch.validation.discovery.synthetic import START_MATERIAL, dataset_text
    from stitchswitch.validation.discovery.workflow import discover
    from stitchswitch.validation.measured import parse_measurements

    t0 = time.perf_counter()
    src, vals = case["source"], tuple(case["values"])
    data = parse_measurements(dataset_text(src, vals, seed=case["seed"], executor=executor),
                              case["id"])
    clean = parse_measurements(dataset_text(src, vals, seed=case["seed"], noise=False,
                                            executor=executor), case["id"]).keypoints()
    t1 = time.perf_counter()
    disc = discover(data, START_MATERIAL, executor=executor)
    seconds = time.perf_counter() - t1
    s = disc.summary
    va = disc.split == "val"
    gap_b = np.mean(np.abs(disc.before[va] - clean[va]), axis=0)
    gap_a = np.mean(np.abs(disc.after[va] - clean[va]), axis=0)
    rank = {r["effect"]: r["rank"] for r in s["ranking"]}
    floor = np.mean(np.abs(clean[va] - disc.measured[va]), axis=0)
    oracle = _oracle(disc, clean, src, vals, executor) if src in LIBRARY else None
    return {
        **case, "named": s["missing_effect"], "significant": s["significant"],
        "fitted": s["effect_parameters"], "decision": s["decision"],
        "true_rank": rank.get(src), "top": s["ranking"][0]["effect"],
        "top_p": s["ranking"][0]["p_value"],
        "top_corr": s["ranking"][0]["signature"]["correlation"],
        "ranking": [(r["effect"], r["score"], r["p_value"], r["signature"]["correlation"],
                     r["effect_parameters"]) for r in s["ranking"]],
        "start_cv": s["starting_model"]["cv_score_mm2"],
        "val_mae_before": {q: s["before"][q]["mae_mm"] for q in QUANT},
        "val_mae_after": {q: s["after"][q]["mae_mm"] for q in QUANT},
        "gap_before": dict(zip(QUANT, map(float, gap_b))),
        "gap_after": dict(zip(QUANT, map(float, gap_a))),
        "systematic_before": [q for q in QUANT if s["residuals_before"][q]["systematic"]],
        "noise_floor": dict(zip(QUANT, map(float, floor))),
        "oracle": oracle,
        "seconds": seconds, "data_seconds": t1 - t0, "solves": disc.solves,
    }


def _oracle(disc, clean, source, values, executor) -> dict:
    """The hidden effect's model fitted to the noisy training rows of ``disc`` (a finished
    discovery run) from the true parameters (the workflow's least squares and step budget):
    its validation gap and noisy MAE."""
    from stitchswitch.validation.discovery.evaluate import Evaluator
    from stitchswitch.validation.discovery.fit import fit
    from stitchswitch.validation.discovery.space import BASE_FREE, ModelSpec
    from stitchswitch.validation.discovery.synthetic import START_MATERIAL, TRUE_MATERIAL
    from stitchswitch.validation.discovery.workflow import DiscoveryConfig

    tr, va = disc.split == "train", disc.split == "val"
    designs = np.column_stack([disc.diameter_mm, disc.fill])
    spec = ModelSpec(START_MATERIAL, source, BASE_FREE)
    ev = Evaluator(executor)
    f = fit(spec, ev, designs[tr], disc.measured[tr], spec.encode(TRUE_MATERIAL, values),
            max_nfev=DiscoveryConfig().fit_max_nfev)
    pred = ev.one(spec, f.x, designs[va])
    return {"effect_parameters": dict(zip(spec.names[len(BASE_FREE):],
                                          spec.decode(f.x)[1][source])),
            "train_mse_mm2": f.mse_mm2,
            "gap": dict(zip(QUANT, map(float, np.mean(np.abs(pred - clean[va]), axis=0)))),
            "val_mae": dict(zip(QUANT, map(float, np.mean(np.abs(pred - disc.measured[va]),
                                                          axis=0))))}


def _per_q(stat, values: dict) -> dict:
    """{quantity: stat(list)} with NaN for an empty list."""
    return {q: float(stat(v)) if v else float("nan") for q, v in values.items()}


def _red(before, after):
    return 1.0 - after / before if before > 0 else float("nan")


def summarize(results: list) -> dict:
    from stitchswitch.validation.discovery.effects import LIBRARY

    lib = [r for r in results if r["source"] in LIBRARY]
    null = [r for r in results if r["source"] is None]
    ctrl = [r for r in results if r["source"] == "gravity_sag"]
    fem = [r for r in results if r["source"] == "fem_shell"]
    correct = [r for r in lib if r["named"] == r["source"]]
    red = {q: [_red(r["gap_before"][q], r["gap_after"][q]) for r in correct] for q in ("h", "r_a")}
    red_noisy = {q: [_red(r["val_mae_before"][q], r["val_mae_after"][q]) for r in correct]
                 for q in ("h", "r_a")}
    both = [r for r in correct if all(_red(r["gap_before"][q], r["gap_after"][q]) >= 0.5
                                      for q in ("h", "r_a"))]
    with_oracle = [r for r in lib if r.get("oracle")]
    oracle_both = [r for r in with_oracle
                   if all(_red(r["gap_before"][q], r["oracle"]["gap"][q]) >= 0.5
                          for q in ("h", "r_a"))]
    achievable = {q: [_red(r["val_mae_before"][q], r["noise_floor"][q]) for r in lib
                      if "noise_floor" in r] for q in ("h", "r_a")}
    ach_both = [r for r in lib if "noise_floor" in r and
                all(_red(r["val_mae_before"][q], r["noise_floor"][q]) >= 0.5 for q in ("h", "r_a"))]
    # share of the achievable noisy-row reduction that the workflow realizes, where there is
    # one to realize (before at least 0.1 mm above the floor)
    realized = {q: [(r["val_mae_before"][q] - r["val_mae_after"][q]) /
                    (r["val_mae_before"][q] - r["noise_floor"][q]) for r in correct
                    if "noise_floor" in r and r["val_mae_before"][q] - r["noise_floor"][q] >= 0.1]
                for q in ("h", "r_a")}
    # how close the workflow's gap comes to the oracle's (identified cases with an oracle)
    near = [r for r in correct if r.get("oracle") and
            all(r["gap_after"][q] <= r["oracle"]["gap"][q] + 0.25 for q in ("h", "r_a"))]
    secs = [r["seconds"] for r in results]
    per_effect = {n: f"{sum(r['named'] == n for r in lib if r['source'] == n)}/"
                     f"{sum(r['source'] == n for r in lib)}" for n in LIBRARY}
    return {
        "library_cases": len(lib), "identified": len(correct),
        "accuracy": len(correct) / len(lib) if lib else float("nan"),
        "per_effect": per_effect,
        "wrong_name_on_library_data": sum(1 for r in lib if r["named"] not in (None, r["source"])),
        "missed_on_library_data": sum(1 for r in lib if r["named"] is None),
        "null_cases": len(null), "false_discoveries_null": sum(r["named"] is not None for r in null),
        "control_cases": len(ctrl),
        "false_discoveries_control": sum(r["named"] is not None for r in ctrl),
        "false_discovery_rate": (sum(r["named"] is not None for r in null + ctrl) /
                                 len(null + ctrl)) if null + ctrl else float("nan"),
        "fem_named": [r["named"] for r in fem],
        "median_gap_reduction": _per_q(np.median, red),
        "median_val_mae_reduction_noisy": _per_q(np.median, red_noisy),
        "cases_h_and_r_a_gap_halved": f"{len(both)}/{len(correct)}",
        "oracle_h_and_r_a_gap_halved": f"{len(oracle_both)}/{len(with_oracle)}",
        "cases_within_0.25mm_of_oracle_gap": f"{len(near)}/{len(correct)}",
        "median_achievable_val_mae_reduction_noisy": _per_q(np.median, achievable),
        "max_achievable_val_mae_reduction_noisy": _per_q(np.max, achievable),
        "cases_where_halving_noisy_h_and_r_a_is_possible": f"{len(ach_both)}/{len(lib)}",
        "median_share_of_achievable_reduction_realized": _per_q(np.median, realized),
        "cases_with_achievable_reduction": {q: len(v) for q, v in realized.items()},
        "seconds_median": float(np.median(secs)) if secs else float("nan"),
        "seconds_max": float(np.max(secs)) if secs else float("nan"),
        "targets": {"accuracy_ge_0.9": bool(lib) and len(correct) / len(lib) >= 0.9,
                    "no_false_discovery_on_null": all(r["named"] is None for r in null),
                    "runtime_le_600s": bool(secs) and max(secs) <= 600.0},
    }


def _pair(q) -> str:
    """'h r_a' of a per-quantity dict, or a dash."""
    return f"{q['h']:5.2f} {q['r_a']:5.2f}" if q else f"{'-':>11s}"


def table(results: list, summary: dict) -> str:
    lines = [f"{'case':22s} {'strength':>10s} {'named':20s} {'p':>8s} {'gap h':>13s} "
             f"{'gap r_a':>13s} {'oracle':>11s} {'val MAE h':>13s} {'val MAE r_a':>13s} "
             f"{'floor':>11s} {'time':>6s}"]
    for r in results:
        st = ", ".join(f"{v:.4g}" for v in r["values"]) or "-"
        fit = ", ".join(f"{v:.3g}" for v in r["fitted"].values())
        named = (r["named"] or "none") + (f" ({fit})" if fit else "")
        lines.append(
            f"{r['id']:22s} {st:>10s} {named[:20]:20s} {r['top_p']:8.2g} "
            f"{r['gap_before']['h']:5.2f}->{r['gap_after']['h']:5.2f} "
            f"{r['gap_before']['r_a']:5.2f}->{r['gap_after']['r_a']:5.2f} "
            f"{_pair((r.get('oracle') or {}).get('gap'))} "
            f"{r['val_mae_before']['h']:5.2f}->{r['val_mae_after']['h']:5.2f} "
            f"{r['val_mae_before']['r_a']:5.2f}->{r['val_mae_after']['r_a']:5.2f} "
            f"{_pair(r.get('noise_floor'))} {r['seconds']:5.0f}s")
    s = summary
    lines += ["",
              f"identification accuracy: {s['identified']}/{s['library_cases']} = "
              f"{100 * s['accuracy']:.0f} % (target >= 90 %); per effect {s['per_effect']}",
              f"false discoveries: null {s['false_discoveries_null']}/{s['null_cases']} (target 0), "
              f"control gravity_sag {s['false_discoveries_control']}/{s['control_cases']}; "
              f"false-discovery rate {100 * s['false_discovery_rate']:.0f} %",
              f"fem_shell (hoop bending + Poisson on): named {s['fem_named']}",
              f"median gap reduction (identified cases, vs noise-free truth): "
              f"h {100 * s['median_gap_reduction']['h']:.0f} %, r_a "
              f"{100 * s['median_gap_reduction']['r_a']:.0f} %; h and r_a both halved in "
              f"{s['cases_h_and_r_a_gap_halved']}",
              f"oracle (true model fitted from the true parameters): h and r_a gaps both "
              f"halved in {s['oracle_h_and_r_a_gap_halved']}; workflow within 0.25 mm of the "
              f"oracle's gap (h and r_a) in {s['cases_within_0.25mm_of_oracle_gap']}",
              f"median val MAE reduction against the noisy rows: h "
              f"{100 * s['median_val_mae_reduction_noisy']['h']:.0f} %, r_a "
              f"{100 * s['median_val_mae_reduction_noisy']['r_a']:.0f} %; achievable (down to "
              f"the noise floor) median h "
              f"{100 * s['median_achievable_val_mae_reduction_noisy']['h']:.0f} %, r_a "
              f"{100 * s['median_achievable_val_mae_reduction_noisy']['r_a']:.0f} % (max h "
              f"{100 * s['max_achievable_val_mae_reduction_noisy']['h']:.0f} %, r_a "
              f"{100 * s['max_achievable_val_mae_reduction_noisy']['r_a']:.0f} %); a 50 % "
              f"reduction of both is possible at all in "
              f"{s['cases_where_halving_noisy_h_and_r_a_is_possible']} library cases",
              f"share of the achievable noisy-row reduction realized (identified cases with "
              f">= 0.1 mm to gain): median h "
              f"{100 * s['median_share_of_achievable_reduction_realized']['h']:.0f} % "
              f"({s['cases_with_achievable_reduction']['h']} cases), r_a "
              f"{100 * s['median_share_of_achievable_reduction_realized']['r_a']:.0f} % "
              f"({s['cases_with_achievable_reduction']['r_a']} cases)",
              f"runtime per workflow run: median {s['seconds_median']:.0f} s, max "
              f"{s['seconds_max']:.0f} s (target <= 600 s)"]
    for k, v in s["targets"].items():
        lines.append(f"  {'PASS' if v else 'FAIL'}  {k}")
    return "\n".join(lines)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--per-effect", type=int, default=3)
    ap.add_argument("--null", type=int, default=3)
    ap.add_argument("--no-fem", action="store_true")
    ap.add_argument("--no-control", action="store_true", help="skip the gravity_sag datasets")
    ap.add_argument("--scale", type=float, default=1.0,
                    help="multiply the drawn hidden strengths (kept inside 95 %% of the bounds): "
                         "how the yardsticks move when the effect dominates the noise")
    ap.add_argument("--only", default=None, help="comma-separated case ids to run")
    ap.add_argument("--log", default=None, help="JSON lines file: append results, skip done cases")
    ap.add_argument("--json", action="store_true")
    args = ap.parse_args(argv)

    from stitchswitch.errors import InvalidInputError
    from stitchswitch.executor import make_executor

    if args.scale <= 0:
        ap.error(f"--scale: {args.scale!r} must be positive")
    todo = cases(args.per_effect, args.null, not args.no_fem, args.scale, not args.no_control)
    if args.only:
        keep = set(args.only.split(","))
        todo = [c for c in todo if c["id"] in keep]
    done = {}
    if args.log and pathlib.Path(args.log).exists():
        for line in pathlib.Path(args.log).read_text().splitlines():
            if line.strip():
                r = json.loads(line)
                done[r["id"]] = r
    results = []
    with make_executor(args.workers) as ex:
        for case in todo:
            if case["id"] in done and done[case["id"]]["seed"] == case["seed"]:
                results.append(done[case["id"]])
                continue
            try:
                r = run_case(case, ex if args.workers > 1 else None)
            except InvalidInputError as exc:       # e.g. a strength whose data do not solve
                r = {**case, "error": str(exc)}
                print(f"{r['id']}: no dataset: {exc}", file=sys.stderr, flush=True)
            else:
                print(f"{r['id']}: named {r['named']} in {r['seconds']:.0f} s", file=sys.stderr,
                      flush=True)
            results.append(r)
            if args.log:
                with open(args.log, "a") as f:
                    f.write(json.dumps(r, default=float) + "\n")
    failed = [r for r in results if "error" in r]
    results = [r for r in results if "error" not in r]
    summary = summarize(results)
    summary["cases_without_data"] = {r["id"]: r["error"] for r in failed}
    if args.json:
        print(json.dumps({"cases": results, "summary": summary}, indent=1, default=float))
    else:
        print(table(results, summary))
        for cid, why in summary["cases_without_data"].items():
            print(f"  {cid}: no dataset ({why})")
    return 0 if all(summary["targets"].values()) else 1


if __name__ == "__main__":
    sys.exit(main())
