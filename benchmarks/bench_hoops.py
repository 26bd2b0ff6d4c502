"""Benchmark: hoop grouping by MIP (cvxpy + HiGHS) against first-fit decreasing.

Random seeded layouts of 20, 40 and 60 patches, in both modes, on the Janome 550E's hoops:

* garment: one rectangular piece, 420 x 520 mm relaxed (714 x 884 mm stretched by 1.7); patch
  diameters uniform in [20, 70] mm (on the stretched fabric), at least 10 mm apart and far
  enough from the edge to be hooped;
* free: the same number of patches with diameters uniform in [30, 90] mm, 10 mm spacing.

Targets: the MIP never uses more hoopings than first-fit decreasing, and 60 patches are grouped
in <= 10 s (the whole grouping: candidates or hoop loads, greedy methods and HiGHS, with the
default 10 s time limit). Also printed: the proven lower bound, whether HiGHS proved optimality
(garment: over the candidate placements; free: over the generated hoop loads) and, in garment
mode, hoopings and frame conflicts (after ordering) before and after planning them together:
"before" groups for the fewest hoopings and orders afterwards; "after" is the default
(``grouping.conflict_plan``: conflicts first, then hoopings). Target: never more conflicts
after than before.

    python benchmarks/bench_hoops.py [--seeds 3] [--sizes 20,40,60] [--hoop SQ14b]
        [--modes garment,free] [--json]
"""
from __future__ import annotations

import argparse
import json
import time

import numpy as np

ETA = 1.7


def layout(n: int, seed: int, free: bool):
    from stitchswitch.layout.fabrication.grouping.footprints import Footprint, StretchedPiece
    w, h = 420 * ETA, 520 * ETA
    rng = np.random.default_rng(seed)
    dmin, dmax = (30.0, 90.0) if free else (20.0, 70.0)
    rows = []
    while len(rows) < n:
        d = rng.uniform(dmin, dmax)
        m = d / 2 + 35.0
        x, y = rng.uniform(m, w - m), rng.uniform(m, h - m)
        if free or all(np.hypot(x - a, y - b) >= (d + c) / 2 + 10.0 for a, b, c in rows):
            rows.append((x, y, d))
    feet = tuple(Footprint(f"p{i + 1}", "front", (float(x), float(y)), float(d))
                 for i, (x, y, d) in enumerate(rows))
    piece = StretchedPiece("front", np.array([[0, 0], [w, 0], [w, h], [0, h]], dtype=float))
    return feet, (piece,)


def run_one(n, seed, mode, hoops, time_limit_s):
    from stitchswitch.layout.fabrication.grouping.group import group
    from stitchswitch.layout.fabrication.order import order_hoopings
    feet, pieces = layout(n, seed, mode == "free")
    row = {}
    runs = ((False, "before_"), (True, "")) if mode == "garment" else ((True, ""),)
    for avoid, prefix in runs:
        t, c = time.perf_counter(), time.process_time()
        g = group(feet, pieces, hoops, mode, time_limit_s, avoid_conflicts=avoid)
        seconds, cpu = time.perf_counter() - t, time.process_time() - c
        conflicts = len(order_hoopings(g.hoopings, feet).conflicts) if mode == "garment" else 0
        row.update({f"{prefix}hoopings": g.count, f"{prefix}conflicts": conflicts,
                    f"{prefix}seconds": seconds, f"{prefix}cpu_s": cpu})
    r = g.report
    return {"mode": mode, "patches": n, "seed": seed, "mip_hoopings": r.fewest_hoopings or g.count,
            "ffd_hoopings": r.greedy_hoopings, "lower_bound": r.hoopings_lower_bound,
            "hoop_types": g.hoop_types, "method": r.method, "status": r.status,
            "optimal": r.optimal, "mip_gap": r.mip_gap, "candidates": r.candidates,
            "conflicts_exact": r.conflicts_exact, **row}


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--seeds", type=int, default=3, help="layouts per size and mode")
    ap.add_argument("--sizes", default="20,40,60")
    ap.add_argument("--hoop", default=None, help="use only this hoop of the 550E")
    ap.add_argument("--time-limit", type=float, default=10.0)
    ap.add_argument("--modes", default="garment,free", help="garment, free or both")
    ap.add_argument("--json", action="store_true")
    args = ap.parse_args(argv)

    import cvxpy  # noqa: F401  - import time is not grouping time

    from stitchswitch.layout.embroidery.machines import default_machine
    machine = default_machine()
    hoops = (machine.hoop(args.hoop),) if args.hoop else machine.hoops
    sizes = [int(s) for s in args.sizes.split(",")]
    rows = [run_one(n, seed, mode, hoops, args.time_limit)
            for mode in args.modes.split(",") for n in sizes for seed in range(1, args.seeds + 1)]
    biggest = max(sizes)
    slowest = max(r["seconds"] for r in rows if r["patches"] == biggest)
    garment = [r for r in rows if r["mode"] == "garment"]
    targets = {
        "never_more_than_ffd": all(r["mip_hoopings"] <= r["ffd_hoopings"] for r in rows),
        f"{biggest}_patches_le_10s": slowest <= 10.0,
        "conflicts_never_more_than_before": all(r["conflicts"] <= r["before_conflicts"]
                                                for r in garment),
    }
    result = {"hoops": [h.name for h in hoops], "time_limit_s": args.time_limit, "rows": rows,
              "targets": targets}
    if args.json:
        print(json.dumps(result, indent=1))
        return 0
    head = (f"{'mode':<8}{'n':>4}{'seed':>5}{'MIP':>5}{'FFD':>5}{'LB':>4}{'types':>6}  "
            f"{'method':<16}{'optimal':>8}{'gap':>7}{'cands':>7}  {'before h/c':>10}"
            f"{'after h/c':>10}{'exact':>6}{'time s':>8}{'cpu s':>7}")
    print(f"hoops: {', '.join(result['hoops'])}; time limit {args.time_limit:g} s; h/c: "
          "hoopings / frame conflicts after ordering, before = fewest hoopings then order, "
          "after = conflicts first (conflict_plan); time and cpu: the 'after' grouping")
    print(head)
    print("-" * len(head))
    for r in rows:
        gap = "-" if r["mip_gap"] is None else f"{100 * r['mip_gap']:.1f}%"
        before = (f"{r['before_hoopings']}/{r['before_conflicts']}" if "before_hoopings" in r
                  else "-")
        after = f"{r['hoopings']}/{r['conflicts']}" if r["mode"] == "garment" else f"{r['hoopings']}/-"
        exact = ("yes" if r["conflicts_exact"] else "no") if r["mode"] == "garment" else "-"
        print(f"{r['mode']:<8}{r['patches']:>4}{r['seed']:>5}{r['mip_hoopings']:>5}"
              f"{r['ffd_hoopings']:>5}{r['lower_bound']:>4}{r['hoop_types']:>6}  "
              f"{r['method']:<16}{'yes' if r['optimal'] else 'no':>8}{gap:>7}"
              f"{r['candidates']:>7}  {before:>10}{after:>10}{exact:>6}{r['seconds']:>8.2f}"
              f"{r['cpu_s']:>7.2f}")
    if garment:
        print(f"garment: frame conflicts {sum(r['before_conflicts'] for r in garment)} before, "
              f"{sum(r['conflicts'] for r in garment)} after; hoopings "
              f"{sum(r['before_hoopings'] for r in garment)} before, "
              f"{sum(r['hoopings'] for r in garment)} after")
    for mode in args.modes.split(","):
        sel = [r for r in rows if r["mode"] == mode]
        print(f"{mode}: MIP {sum(r['mip_hoopings'] for r in sel)} hoopings in total, first-fit "
              f"decreasing {sum(r['ffd_hoopings'] for r in sel)}; fewer in "
              f"{sum(r['mip_hoopings'] < r['ffd_hoopings'] for r in sel)} of {len(sel)} layouts")
    for k, v in targets.items():
        print(f"target {k}: {'met' if v else 'NOT met'}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
