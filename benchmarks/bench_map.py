"""Benchmark: the design-space map (its targets).

* the full default grid (86 diameters x 51 fills) built in <= 10 s on this 2-core machine,
* 1,000 off-grid patches queried in <= 50 ms (keypoints and profiles),
* the first query after installation (a fresh interpreter: import, load the shipped map,
  query) in < 1 s.

    python benchmarks/bench_map.py [--workers N] [--json]
"""
from __future__ import annotations

import argparse
import json
import subprocess
import sys
import time

import numpy as np

FIRST_QUERY = """
import time
t = time.perf_counter()
from stitchswitch.reduced.design_space.cache import default_map
q = default_map().query(40.0, 0.8)
print(time.perf_counter() - t)
"""


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--json", action="store_true")
    args = ap.parse_args(argv)

    from stitchswitch.reduced.design_space import precompute
    from stitchswitch.reduced.design_space.cache import default_map

    t = time.perf_counter()
    dmap = precompute.build(workers=args.workers)
    build_s = time.perf_counter() - t

    shipped = default_map()
    rng = np.random.default_rng(0)
    d, p = rng.uniform(15, 100, 1000), rng.uniform(0.5, 1.0, 1000)
    shipped.query(d, p, profiles=True)
    kp_ms = min(_time(lambda: shipped.query(d, p)) for _ in range(5)) * 1e3
    prof_ms = min(_time(lambda: shipped.query(d, p, profiles=True)) for _ in range(5)) * 1e3
    first = [float(subprocess.run([sys.executable, "-c", FIRST_QUERY], capture_output=True,
                                  text=True, check=True).stdout) for _ in range(3)]
    same = bool(np.array_equal(dmap.h_mm, shipped.h_mm))

    result = {
        "grid": list(dmap.shape), "workers": args.workers, "build_s": build_s,
        "query_1000_keypoints_ms": kp_ms, "query_1000_with_profiles_ms": prof_ms,
        "first_query_s": max(first), "rebuilt_equals_shipped": same,
        "targets": {"build_le_10s": build_s <= 10.0, "query_le_50ms": prof_ms <= 50.0,
                    "first_query_lt_1s": max(first) < 1.0},
    }
    if args.json:
        print(json.dumps(result, indent=1))
    else:
        print(f"full grid {dmap.shape[0]} x {dmap.shape[1]} on {args.workers} workers: "
              f"{build_s:.1f} s (target <= 10 s); identical to the shipped map: {same}")
        print(f"1000 queries: keypoints {kp_ms:.2f} ms, with profiles {prof_ms:.1f} ms (target <= 50 ms)")
        print(f"first query in a fresh interpreter: {max(first):.2f} s (worst of 3; target < 1 s)")
        for name, ok in result["targets"].items():
            print(f"  {'PASS' if ok else 'FAIL'}  {name}")
    return 0 if all(result["targets"].values()) else 1


def _time(f) -> float:
    t = time.perf_counter()
    f()
    return time.perf_counter() - t


if __name__ == "__main__":
    sys.exit(main())
