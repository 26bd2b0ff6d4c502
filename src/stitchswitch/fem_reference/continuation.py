"""Prestretch continuation: the shell reference solved from the flat sheet, independently of the
reduced model.

The rest-metric excess is scaled by t, lambda(t) = 1 + t (lambda - 1) (``ShellModel.prestretched``,
as the reduced model's ``Grid.with_lambda_scale``): t = 0 is the flat, stress-free sheet (the
exact minimizer), t = 1 the design. t is stepped from 0 to 1 and every stage runs Newton
(``ShellModel.solve(..., globalization="eigen")``) from the previous stage's state:

* Seed. Flat is an equilibrium at every t (the z -> -z symmetry), so before each stage whose apex
  is below half the seed, z is raised to at least the seed bump
  ``SEED_FRACTION R_b (1 - (S / R_b)^2)^2`` (zero outside the patch, flat at the pole): once flat
  is unstable, Newton leaves it on the popped-up side. A stage that ends popped down is mirrored
  (z -> -z, an exact symmetry of the energy), so the pop-up branch is always the one followed.
* Stages. The first step is ``INITIAL_STEP``; after a stage that converged (tolerance ``tol``)
  the step grows by ``STEP_GROWTH``, up to ``MAX_STEP`` (not right after a retried stage).
  Below and near the buckling onset the sheet is nearly free (slack fabric and a soft buckling
  mode), and Newton converges slowly there, so an intermediate stage is also accepted when its
  ``STAGE_MAX_ITER`` iterations lowered the residual (its state only starts the next stage).
  A stage is rejected, and the step halved (down to ``MIN_STEP``), when the residual did not
  fall or when a meridional stretch (quadrature points and nodes) fell below ``STRETCH_BOUND``
  times its value at the previous stage: a large step can otherwise jump to another local
  minimum (on small patches, one with the meridian pinched at the pole). The last stage (t = 1)
  must converge, within ``FINAL_MAX_ITER`` iterations.
* Snaps. Where the step has shrunk to ``MIN_STEP`` and the stage still fails, the followed
  branch ends at a limit point (a fold of the equilibrium path: the sheet snaps). The stage is
  then run once more with ``FINAL_MAX_ITER`` iterations, so that Newton can reach the branch the
  sheet snaps to; it is accepted if it converges (and passes the stretch test).
* Certificate: the residual of the last stage, and the lowest eigenvalue of the (scaled) free
  Hessian at the result (``lowest_eigenvalue``; > 0 is a local minimum, not only a stationary
  point).

Everything is deterministic. Measured on the nine ``fem-check`` designs: docs/fem-reference.md.
"""
from __future__ import annotations

import time
from dataclasses import dataclass, replace

import numpy as np

from stitchswitch.fem_reference.shell import STRETCH_BOUND, ShellModel, ShellSolution

INITIAL_STEP = 0.1
MAX_STEP = 0.25
STEP_GROWTH = 2.0
MIN_STEP = 1.0 / 512
STAGE_MAX_ITER = 60
FINAL_MAX_ITER = 300
SEED_FRACTION = 0.1       # seed bump height / R_b
STARTS = ("reduced", "continuation")
#: The default start of ``fem-check`` and ``fem-solve``: the continuation converges on all nine
#: fem-check designs (80 and 40 elements) to the equilibrium of the reduced start
#: (docs/fem-reference.md, benchmarks/bench_fem.py).
DEFAULT_START = "continuation"


@dataclass(frozen=True)
class Stage:
    t: float                  # prestretch fraction of this stage
    iterations: int
    residual: float
    converged: bool
    accepted: bool
    apex_mm: float            # z(0) after the stage (after mirroring)


@dataclass(frozen=True)
class ContinuationResult:
    solution: ShellSolution   # at t = 1; iterations and solve_s are the whole path's
    stages: tuple[Stage, ...]
    lowest_eigenvalue: float  # of the scaled free Hessian at the solution

    @property
    def converged(self) -> bool:
        return bool(self.solution.converged)

    def as_dict(self) -> dict:
        return {"converged": self.converged, "iterations": self.solution.iterations,
                "solve_s": self.solution.solve_s, "stages": len(self.stages),
                "rejected_stages": sum(not s.accepted for s in self.stages),
                "lowest_eigenvalue": self.lowest_eigenvalue}


def seed_bump(model: ShellModel) -> tuple[np.ndarray, np.ndarray]:
    """Values and slopes of the seed bump at the mesh nodes (mm)."""
    rb = model.rb
    s = np.clip(model.nodes / rb, 0.0, 1.0)
    a = SEED_FRACTION * rb
    return a * (1.0 - s * s) ** 2, -4.0 * a * s * (1.0 - s * s) / rb


def seeded(model: ShellModel, x: np.ndarray) -> np.ndarray:
    """``x`` with z raised to at least the seed bump if its apex is below half the seed."""
    bump, slope = seed_bump(model)
    values, derivs = model.n + model._value_dofs, model.n + model._deriv_dofs
    if x[values[0]] >= 0.5 * bump[0]:
        return x
    out = x.copy()
    up = bump > out[values]
    out[values[up]], out[derivs[up]] = bump[up], slope[up]
    return out


def mirrored(model: ShellModel, x: np.ndarray) -> np.ndarray:
    """The z -> -z image (same energy) if the apex is below the rim, else ``x``."""
    if x[model.n + model._value_dofs[0]] >= 0.0:
        return x
    out = x.copy()
    out[model.n:] *= -1.0
    return out


def prestretch_continuation(model: ShellModel, *, tol: float = 1e-9) -> ContinuationResult:
    """Follow the pop-up equilibrium of ``model`` from the flat sheet (t = 0) to t = 1."""
    t0 = time.perf_counter()
    x = model.flat_state()
    apex = model.n + model._value_dofs[0]
    t, step, iterations, retried, snapping = 0.0, INITIAL_STEP, 0, False, False
    stages: list[Stage] = []
    sol = None
    while True:
        t_next = min(1.0, t + step)
        final = t_next >= 1.0
        stage_model = model.prestretched(t_next)
        start = seeded(model, x)
        _, g, _ = stage_model.derivatives(start)
        start_residual = float(np.max(np.abs(g[model.free])))
        long_stage = final or snapping
        sol = stage_model.solve(start, tol=tol, max_iter=FINAL_MAX_ITER if long_stage else STAGE_MAX_ITER,
                                globalization="eigen")
        iterations += sol.iterations
        x_new = mirrored(model, sol._x)
        ok = sol.converged or (not long_stage and sol.residual < start_residual)
        ok = ok and bool(np.all(model.stretches(x_new) >= STRETCH_BOUND * model.stretches(x)))
        stages.append(Stage(t_next, sol.iterations, sol.residual, sol.converged, ok,
                            float(x_new[apex])))
        if ok:
            x, t = x_new, t_next
            if final:
                break
            if sol.converged and not retried:
                step = min(STEP_GROWTH * step, MAX_STEP)
            retried = snapping = False
            continue
        retried = True
        if step <= MIN_STEP:
            if snapping or final:
                break
            snapping = True          # a limit point: let Newton find the branch the sheet snaps to
            continue
        step *= 0.5
    if sol._x is not x:                          # mirrored (or the path stalled): re-certify
        E, g, _ = model.derivatives(x)
        residual = float(np.max(np.abs(g[model.free])))
        sol = model._solution(x, E, residual, bool(sol.converged and residual <= tol), 0, t0)
    result = replace(sol, iterations=iterations, solve_s=time.perf_counter() - t0)
    object.__setattr__(result, "_x", x)
    return ContinuationResult(result, tuple(stages), model.lowest_eigenvalue(x))


def solve_reference(model: ShellModel, start: str = "reduced", reduced=None, *,
                    max_iter: int = 300) -> ShellSolution:
    """The reference equilibrium of ``model``, started as ``start`` says: ``"reduced"`` runs
    Newton from the reduced model's equilibrium ``reduced`` (a ``reduced.solvers.solve.Solution``;
    solved here if None), ``"continuation"`` runs ``prestretch_continuation`` from the flat sheet
    and never calls the reduced model."""
    if start == "continuation":
        return prestretch_continuation(model).solution
    if start != "reduced":
        from stitchswitch.errors import InvalidInputError

        raise InvalidInputError(f"start: {start!r} is not one of {', '.join(STARTS)}")
    if reduced is None:
        from stitchswitch.reduced.solvers.solve import solve

        reduced = solve(model.patch, model.material)
    return model.solve(model.start_from_profile(reduced.R_mm, reduced.r_mm, reduced.z_mm),
                       max_iter=max_iter)
