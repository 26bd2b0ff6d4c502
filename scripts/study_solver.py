"""The certified solver's robustness and where its time goes (docs/model.md, "Speed"): the
figures there are this script's output.

Robustness: every design of a sweep d = 10-150 mm every 5 mm, p = 0.05-1.0 every 0.05 (580
designs) solved cold with the default material: how many certify, and the Newton iterations.
Cost per iteration: CPU time of each compiled part of one Newton iteration at the solution of
d = 55 mm, p = 1.0 (the energy with its Hessian, one line-search trial, the bordered
restriction, factor and solve, the polar step), each the mean of many calls.

Work per iteration: on the 21 designs of ``benchmarks/bench_solver.py``, the loop's source run
interpreted with its compiled parts counted (``newton_loop.iterate`` with the fused energy;
the same iterates as the compiled loop):
energy evaluations of the line search, retraction points (a point with a segment of zero
length is rejected before its energy) and Cholesky factorizations (the shift search) per
iteration, and the share of iterations of each kind (a step cut by the line search, a shifted
Hessian, a failed factorization, an active-set change, a plain Newton step). With the part
costs this gives the floor of an iteration: one Hessian, one trial, one factorization.

Usage: python scripts/study_solver.py [--json]
"""
from __future__ import annotations

import json
import sys
import time

import numpy as np
from numba import njit

from stitchswitch import DEFAULT_MATERIAL, Patch, solve
from stitchswitch.reduced.model.discretization import make_grid
from stitchswitch.reduced.model.terms import ALL_TERMS
from stitchswitch.reduced.model.terms.segment import BANDWIDTH
from stitchswitch.reduced.solvers import bordered, fused, retraction, step

DIAMETERS_MM = np.arange(10.0, 150.0 + 1e-9, 5.0)
FILLS = np.round(np.arange(0.05, 1.0 + 1e-9, 0.05), 2)


@njit
def _repeat(f, args, n):
    for _ in range(n):
        f(*args)


def _cpu_us(f, *args, n: int = 3000) -> float:
    """CPU time of one call of the compiled ``f``, called from compiled code (as the Newton loop
    calls it: no dispatch from Python in the figure)."""
    _repeat(f, args, 1)
    t = time.process_time()
    _repeat(f, args, n)
    return (time.process_time() - t) / n * 1e6


def robustness() -> dict:
    its, certified = [], 0
    for d in DIAMETERS_MM:
        for p in FILLS:
            sol = solve(Patch(float(d), float(p)))
            its.append(sol.iterations)
            certified += sol.certified
    return {"designs": len(its), "certified": certified, "median_iterations": float(np.median(its)),
            "max_iterations": int(max(its))}


BENCH_DESIGNS = [(d, p) for d in (15, 25, 40, 55, 70, 85, 100) for p in (0.6, 0.8, 1.0)]


def work_per_iteration() -> dict:
    """Counts per Newton iteration of the line-search energies, retraction points and
    factorizations on the benchmark designs (the compiled parts counted from Python), and what
    kind of iteration each one is: its accepted step cut by the line search (and cut to 1/16 or
    less), its Hessian shifted, a failed factorization in its shift search, its active set
    changed from the previous iteration, or a plain Newton step (full, unshifted)."""
    from contextlib import ExitStack
    from types import SimpleNamespace
    from unittest import mock

    from stitchswitch.reduced.solvers import newton, newton_loop

    counts = {"energy": 0, "point": 0, "factor": 0}
    events = []                    # the loop's calls in order, to split into iterations

    def counted(name, f):
        def g(*args):
            counts[name] += 1
            events.append((name, args[-1] if name == "point" else None))
            return f(*args)
        return g

    def stationarity(g, u):
        out = step.stationarity(g, u)
        events.append(("free", out[1]))
        return out

    def direction(*args):
        d, shift, raised = step.direction.py_func(*args)
        events.append(("direction", shift))
        return d, shift, raised

    energy = counted("energy", fused.energy)

    def evaluator(grid, terms):
        c = fused.coefficients(terms, grid)

        def iterate(r, z, c, tol, max_iter, it, shift):
            events.append(("start", None))
            return newton_loop.iterate(r, z, c, tol, max_iter, it, shift, fused.derivatives, energy)
        return iterate, c, lambda r, z: fused.energy(r, z, c)

    with ExitStack() as stack:
        stack.enter_context(mock.patch.object(newton, "_evaluator", evaluator))
        stack.enter_context(mock.patch.object(newton_loop, "point", counted("point", retraction.point)))
        stack.enter_context(mock.patch.object(newton_loop, "stationarity", stationarity))
        stack.enter_context(mock.patch.object(newton_loop, "direction", direction))
        stack.enter_context(mock.patch.object(step, "bordered", SimpleNamespace(
            envelope_rows=bordered.envelope_rows, factor_with=counted("factor", bordered.factor_with),
            solve=bordered.solve)))
        iterations = sum(solve(Patch(float(d), p)).iterations for d, p in BENCH_DESIGNS)
    kinds = _iteration_kinds(events)
    assert kinds.pop("iterations") == iterations
    return {"iterations": iterations,
            "line-search energies per iteration": counts["energy"] / iterations,
            "retraction points per iteration": counts["point"] / iterations,
            "factorizations per iteration": counts["factor"] / iterations,
            **{f"share of iterations: {k}": v / iterations for k, v in kinds.items()}}


def _iteration_kinds(events) -> dict:
    """How many iterations of each kind (``work_per_iteration``) the recorded calls show. An
    iteration starts at its direction: its free drops are the last ``free`` before it (the
    start of the loop's pass), its accepted step the last ``point`` after it."""
    kinds = dict.fromkeys(("cut", "cut to 1/16 or less", "shifted", "a failed factorization",
                           "active set changed", "plain Newton step"), 0)
    n, free, previous, pending = 0, None, None, 0
    current = None                 # [shift, factorizations, alpha] of the open iteration

    def close():
        if current is not None:
            shift, factors, alpha = current
            kinds["cut"] += alpha < 1.0
            kinds["cut to 1/16 or less"] += alpha <= 1.0 / 16.0
            kinds["shifted"] += shift > 0.0
            kinds["a failed factorization"] += factors > 1
            kinds["plain Newton step"] += alpha == 1.0 and shift == 0.0

    for name, value in events:
        if name == "start":
            close()
            current, free, previous = None, None, None
        elif name == "free":
            free = value
        elif name == "factor":
            pending += 1
        elif name == "direction":
            close()
            n += 1
            kinds["active set changed"] += previous is not None and not np.array_equal(free, previous)
            previous = free
            current = [value, pending, 1.0]
        elif name == "point" and current is not None:
            current[2] = value
        if name in ("start", "direction"):
            pending = 0
    close()
    return {"iterations": n, **kinds}


def parts(design=(55.0, 1.0)) -> dict:
    sol = solve(Patch(*design))
    grid = make_grid(Patch(*design), DEFAULT_MATERIAL)
    c = fused.coefficients(ALL_TERMS, grid)
    r, z = sol.r_mm / sol.dr_mm, sol.z_mm / sol.dr_mm
    n = r.size
    grad, hb = np.zeros(2 * n), np.zeros((BANDWIDTH + 1, 2 * n))
    fused.derivatives(r, z, c, grad, hb, True)
    free = step.stationarity(grad, retraction.drops(z))[1]
    dof_map, n_band, m = bordered.indices(n, free)
    At, B, C = bordered.restrict(hb, dof_map, n_band, m)
    d, _, _ = step.direction(At, B, C, grad, dof_map, 0.0, False)
    curve = retraction.polar(r, z, 1e-3 * d)
    from stitchswitch.reduced.model.terms import bending
    from stitchswitch.reduced.model.terms.segment import segment_lengths
    lengths = segment_lengths(r, z)
    return {
        "energy, gradient and Hessian": _cpu_us(fused.derivatives, r, z, c, grad, hb, True),
        "  of which bending": _cpu_us(bending._kernel, r, z, c[5][0], grad, hb, True),
        "line-search trial (point + energy)": _cpu_us(retraction.point, *curve, 1.0)
                                               + _cpu_us(fused.energy, r, z, c),
        "  energy alone": _cpu_us(fused.energy, r, z, c),
        "    of which bending": _cpu_us(bending.energy_lengths, r, z, c[5][0], lengths),
        "restriction": _cpu_us(bordered.restrict, hb, dof_map, n_band, m),
        "factor and solve (direction)": _cpu_us(step.direction, At, B, C, grad, dof_map, 0.0, False),
        "polar step": _cpu_us(retraction.polar, r, z, d),
    }


def main(argv=None) -> int:
    argv = sys.argv[1:] if argv is None else argv
    result = {"robustness": robustness(), "parts_us": parts(), "work": work_per_iteration()}
    us = result["parts_us"]
    result["floor_us_per_iteration"] = (
        us["energy, gradient and Hessian"] + us["line-search trial (point + energy)"]
        + us["restriction"] + us["factor and solve (direction)"] + us["polar step"])
    if "--json" in argv:
        print(json.dumps(result, indent=1))
        return 0
    print(result["robustness"])
    for name, v in us.items():
        print(f"{name:44s} {v:6.1f} us")
    for name, v in result["work"].items():
        print(f"{name:44s} {v:6.2f}")
    print(f"{'floor (one of each part)':44s} {result['floor_us_per_iteration']:6.1f} us")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
