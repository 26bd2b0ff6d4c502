"""Benchmark: the shell of revolution's solve (target <= 2 s) and one full switching path
(target <= 30 s).

Shell solves: the nine fem-check designs (d 25, 50, 90 mm x p 0.6, 0.8, 1.0), default
``ShellParams`` (40 Hermite elements on the patch), ``solve.settled``: Newton from the reduced
model's equilibrium, then from the flat sheet if that does not certify (the reduced solve of the
guess included). Wall and CPU (``time.process_time``) times, since the machine is shared.
Switching paths: ``switching_path`` with the default 24 plate steps on the designs given by
``--paths`` (default d 60 mm, p 0.8).

    python benchmarks/bench_fem.py [--designs D,P;D,P] [--paths D,P;D,P] [--json]
"""
from __future__ import annotations

import argparse
import json
import sys
import time

DESIGNS = tuple((d, p) for d in (25.0, 50.0, 90.0) for p in (0.6, 0.8, 1.0))


def _designs(text, default):
    if not text:
        return default
    return tuple(tuple(float(v) for v in item.split(",")) for item in text.split(";"))


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--designs", default=None, metavar="D,P;D,P")
    ap.add_argument("--paths", default=None, metavar="D,P;D,P")
    ap.add_argument("--json", action="store_true")
    args = ap.parse_args(argv)
    from stitchswitch import DEFAULT_MATERIAL, Patch, solve
    from stitchswitch.fem_reference.revolution.solve import build, settled
    from stitchswitch.fem_reference.snap.path import switching_path

    solve(Patch(40, 0.8))
    build(Patch(40, 0.8))
    solves = []
    for d, p in _designs(args.designs, DESIGNS):
        patch = Patch(d, p)
        problem = build(patch)
        t, c = time.perf_counter(), time.process_time()
        st = settled(problem, patch, DEFAULT_MATERIAL)
        solves.append({"d_mm": d, "fill": p, "shell_s": time.perf_counter() - t,
                       "shell_cpu_s": time.process_time() - c, "iterations": st.iterations,
                       "certified": st.certified, "apex_mm": st.apex_mm,
                       "unknowns": int(problem.free.size)})
    paths = []
    for d, p in _designs(args.paths, ((60.0, 0.8),)):
        t, cpu = time.perf_counter(), time.process_time()
        c = switching_path(Patch(d, p))
        paths.append({"d_mm": d, "fill": p, "path_s": time.perf_counter() - t,
                      "path_cpu_s": time.process_time() - cpu, "inverted": c.inverted,
                      "steps": int(c.w_mm.size - 1), "switching_force_n": c.switching_force_n})
    worst = max(r["shell_s"] for r in solves)
    worst_path = max(r["path_s"] for r in paths)
    ok, ok_path = worst <= 2.0, worst_path <= 30.0
    if args.json:
        print(json.dumps({"solves": solves, "paths": paths, "worst_shell_s": worst,
                          "shell_target_le_2s": ok, "worst_path_s": worst_path,
                          "path_target_le_30s": ok_path}, indent=1))
    else:
        print(f"{'d_mm':>5} {'fill':>4} {'shell_s':>8} {'cpu_s':>6} {'iter':>5} {'certified':>9} "
              f"{'apex_mm':>8} {'unknowns':>8}")
        for r in solves:
            print(f"{r['d_mm']:5g} {r['fill']:4g} {r['shell_s']:8.2f} {r['shell_cpu_s']:6.2f} "
                  f"{r['iterations']:5d} {str(r['certified']):>9} {r['apex_mm']:8.2f} {r['unknowns']:8d}")
        for r in paths:
            print(f"switching path d {r['d_mm']:g} p {r['fill']:g}: {r['path_s']:.1f} s "
                  f"(cpu {r['path_cpu_s']:.1f} s), {r['steps']} steps, "
                  f"inverted {r['inverted']}, switching force {r['switching_force_n']:.4g} N")
        print(f"worst shell solve {worst:.2f} s (target <= 2 s)  {'PASS' if ok else 'FAIL'}")
        print(f"worst switching path {worst_path:.1f} s (target <= 30 s)  {'PASS' if ok_path else 'FAIL'}")
    return 0 if ok and ok_path else 1


if __name__ == "__main__":
    sys.exit(main())
