"""Benchmark: one converged shell-reference solve per design (issue 5 target: <= 10 s).

Nine designs (d 25, 50, 90 mm x p 0.6, 0.8, 1.0), 80 Hermite elements on the patch, started from
the reduced equilibrium (whose time is reported separately).

    python benchmarks/bench_fem.py [--elements 80] [--json]
"""
from __future__ import annotations

import argparse
import json
import sys
import time


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--elements", type=int, default=80)
    ap.add_argument("--json", action="store_true")
    args = ap.parse_args(argv)
    from stitchswitch import Patch, solve
    from stitchswitch.fem_reference.check import DEFAULT_DESIGNS
    from stitchswitch.fem_reference.shell import ShellModel

    solve(Patch(40, 0.8))
    rows = []
    for d, p in DEFAULT_DESIGNS:
        patch = Patch(d, p)
        t = time.perf_counter()
        red = solve(patch)
        t_red = time.perf_counter() - t
        t = time.perf_counter()
        model = ShellModel(patch, red.material, elements_inside=args.elements,
                           growth=1.0 + 3.2 / args.elements)
        sol = model.solve(model.start_from_profile(red.R_mm, red.r_mm, red.z_mm), max_iter=300)
        rows.append({"d_mm": d, "fill": p, "fem_s": time.perf_counter() - t, "reduced_s": t_red,
                     "converged": sol.converged, "iterations": sol.iterations,
                     "dofs": 2 * model.n})
    worst = max(r["fem_s"] for r in rows)
    ok = worst <= 10.0 and all(r["converged"] for r in rows)
    if args.json:
        print(json.dumps({"rows": rows, "worst_s": worst, "target_le_10s": ok}, indent=1))
    else:
        for r in rows:
            print(f"d {r['d_mm']:5g} p {r['fill']:4g}: shell {r['fem_s']:.2f} s ({r['iterations']} "
                  f"Newton iterations, {r['dofs']} dofs, converged {r['converged']}); "
                  f"reduced start {1e3 * r['reduced_s']:.0f} ms")
        print(f"worst shell solve {worst:.2f} s (target <= 10 s)  {'PASS' if ok else 'FAIL'}")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
