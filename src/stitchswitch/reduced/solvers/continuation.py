"""Starting states: the released state, and the release continuation (the fallback).

``released_state`` is the fabric just released from the hoop: flat, with a small upward seed
bump that selects the pop-up side (flat is an equilibrium of every design, by the z -> -z
symmetry). The Newton solver starts there; on the paper's calibration and validation ranges it
reaches an energy at or below both the continuation and the Adam baseline
(benchmarks/bench_solver.py).

``release`` follows the equilibrium from the flat state instead, growing the rest-metric
excess: lambda(t) = 1 + t (lambda - 1), t from 0 (flat, stress free, the exact minimizer) to 1.
It models a slow release; the solver uses it only when the direct solve does not converge,
because on some designs it stays on a pop-up branch of higher energy (d = 25 mm, p = 1.0:
h = 4.0 mm at E = 0.01319 against h = 7.9 mm at E = 0.01205). Each stage starts Newton from the previous stage's
equilibrium; a stage that does not converge is retried with half the step. Before each stage
an upward seed bump is added if the state is (near) flat, so Newton leaves the flat state
once it has become unstable (flat is always an equilibrium, by the z -> -z symmetry).
Everything is deterministic.
"""
from __future__ import annotations

import numpy as np

from stitchswitch.reduced.model.discretization import Grid
from stitchswitch.reduced.solvers import newton

INITIAL_STEP = 0.25
MIN_STEP = 1.0 / 256
STAGE_TOL = 1e-6
STAGE_MAX_ITER = 60
SEED_FRACTION = 0.3      # seed bump height / N_in (dR units)
#: Radius of the seed bump's support / the patch's rest radius: the popped fabric rises outside
#: the patch too, and a bump that reaches past the boundary starts Newton nearer the pop-up
#: (about a fifth fewer iterations than a bump over the patch alone; docs/model.md, "Start").
SEED_SUPPORT_RB = 1.75
#: The second start of a solve that ends flat (``solve``): a flat equilibrium can be a strict
#: local minimum above a popped one (d 72 mm, p 0.60: E 0.017411 flat, 0.017369 at h 7.1 mm).
RETRY_SEED_FRACTION = 0.6


def seed_bump(grid: Grid, fraction: float = SEED_FRACTION) -> np.ndarray:
    """A monotone, pole-flat upward bump over the patch and the fabric next to it (out to
    ``SEED_SUPPORT_RB`` patch radii), zero beyond, dR units; its height is ``fraction`` of the
    patch's rest radius."""
    s = np.clip(grid.R / (SEED_SUPPORT_RB * grid.n_inside), 0.0, 1.0)
    z = fraction * grid.n_inside * (1.0 - s * s) ** 2
    z[0] = z[1]
    return z


def released_state(grid: Grid, fraction: float = SEED_FRACTION) -> tuple[np.ndarray, np.ndarray]:
    """The state at release: the flat hoop configuration (r = R, stress free only for p = 0)
    with the upward seed bump (``seed_bump``), dR units. Both solvers start here by default."""
    return grid.R.copy(), seed_bump(grid, fraction)


def seeded(z: np.ndarray, grid: Grid) -> np.ndarray:
    bump = seed_bump(grid)
    return np.maximum(z, bump) if z[0] < 0.5 * bump[0] else z


def release(grid: Grid, *, tol: float, max_iter: int, terms=None) -> tuple[newton.NewtonResult, int]:
    """Continuation from the flat state; returns the last Newton result and total iterations."""
    r, z = grid.R.copy(), np.zeros(grid.n_nodes)
    t, dt, used = 0.0, INITIAL_STEP, 0
    result = None
    while True:
        t_next = min(1.0, t + dt)
        final = t_next >= 1.0
        budget = max_iter - used if final else min(STAGE_MAX_ITER, max_iter - used)
        result = newton.minimize(grid.with_lambda_scale(t_next), r, seeded(z, grid),
                                 tol=tol if final else STAGE_TOL, max_iter=max(budget, 0),
                                 terms=terms)
        used += result.iterations
        if result.converged:
            if final:
                return result, used
            r, z, t = result.r, result.z, t_next
            dt = min(2.0 * dt, 1.0 - t)
            continue
        if used >= max_iter or dt <= MIN_STEP:
            return result, used
        dt *= 0.5
