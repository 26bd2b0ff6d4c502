"""Certified projected Newton method for the bound-constrained reduced problem.

A projected Newton method (Bertsekas, SIAM J. Control Optim. 20, 1982) in the variables
x = (r_1..r_{N-1}, u_1..u_{N-2}) of ``constraints`` (u_j >= 0 are the segment drops):

1. Active set A = {j : u_j = 0, dE/du_j > 0}: these drops are held at 0. Holding u_j = 0
   merges nodes j and j+1 into one z group, so the Hessian restricted to the free variables
   (r and the group heights) stays banded: groups are runs of consecutive nodes (``step``).
2. The restricted Hessian is factored by banded Cholesky (``banded``). If it is not positive
   definite, a multiple of the identity is added and increased tenfold until it is (Nocedal &
   Wright, Alg. 3.3), so every step is a descent step. The factorization at the solution,
   without shift, tells whether it is a strict local minimum (``second_order``).
3. The step is applied segment by segment in polar form (``retraction``): each segment's
   length and angle change by the first-order amount of the Cartesian Newton step. The two
   agree to first order, but a rotating segment keeps its length instead of stretching along
   the secant, which lets Newton follow the large rotations of the pop-up (3x fewer
   iterations than Cartesian updates in our tests). Angles stay in [-pi, 0] (z' <= 0: the
   projection onto the bounds) and the first segment stays horizontal (z'(0) = 0).
4. Armijo backtracking on that curve. When the predicted decrease is below the rounding
   error of the energy (the last iterations), the full step is accepted if it lowers the
   certificate instead. The energy is +inf outside its domain, so no node
   crosses the axis and no segment folds or collapses.

5. A stationary point whose restricted Hessian is not positive definite is a saddle: the
   solver leaves it along the direction of most negative curvature (``_escape``) and goes on.

Steps 1-4 run in ``newton_loop``: compiled as one numba function for the default energy terms
and their coefficient variants (``fused``), interpreted (the same source) for any other term
tuple. The saddle escape (rare) runs here, in Python.

The result is certified by the max-norm of the projected gradient (``constraints.kkt_residual``);
``converged`` is True only when it is <= ``tol``.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from stitchswitch.reduced.model import assembly
from stitchswitch.reduced.model.discretization import Grid
from stitchswitch.reduced.model.terms import ALL_TERMS
from stitchswitch.reduced.solvers import banded, fused, newton_loop
from stitchswitch.reduced.solvers.retraction import heights, point, polar
from stitchswitch.reduced.solvers.step import reduced_indices

MAX_ESCAPES = 5          # saddle escapes along negative curvature per solve

__all__ = ["MAX_ESCAPES", "NewtonResult", "minimize", "reduced_indices"]


@dataclass(frozen=True)
class NewtonResult:
    r: np.ndarray
    z: np.ndarray
    energy: float
    residual: float
    iterations: int
    converged: bool
    second_order: bool | None
    message: str


def _escape(energy, n_inside, r, z, E, ab, dof_map):
    """Leave a saddle point along the direction of most negative curvature.

    A stationary point whose restricted Hessian is not positive definite is a saddle (for
    example the flat state of a design that buckles: its gradient vanishes by symmetry, so
    Newton cannot leave it). The eigenvector of the smallest eigenvalue is followed on the
    polar curve with the largest step, from half the patch radius down, that lowers the
    energy: first oriented to lift the pole (pop-up), then the other way (the sign bounds can
    clip a direction into an ascent). Returns the new state, or None."""
    lam, v = banded.lowest_mode(ab)
    if lam >= 0:
        return None
    valid = dof_map >= 0
    d = np.where(valid, v[np.maximum(dof_map, 0)], 0.0)
    d /= np.max(np.abs(d))
    if d[1] < 0 or (d[1] == 0 and np.sum(d[1::2]) < 0):
        d = -d
    for sign in (1.0, -1.0):        # pop-up orientation first; the bounds may clip it away
        curve = polar(r, z, sign * d)
        alpha = 0.5 * n_inside
        while alpha > 1e-8:
            ok, r_try, z_try = point(*curve, alpha)
            if ok and energy(r_try, z_try) < E - 1e-12 * abs(E):
                return r_try, z_try
            alpha *= 0.5
    return None


def prepare(grid: Grid, terms=None):
    """(iterate, model, energy) of ``grid`` and ``terms`` (default ``terms.ALL_TERMS``): the
    compiled loop with the fused coefficients when ``terms`` allow it (``fused.coefficients``),
    else the interpreted loop over an ``assembly.Model``. ``minimize`` takes it as
    ``prepared``, so that several starts on one grid compute the coefficients once."""
    terms = ALL_TERMS if terms is None else terms
    coefficients = fused.coefficients(terms, grid)
    if coefficients is not None:
        return (newton_loop.fused_iterate, coefficients,
                lambda r, z: fused.energy(r, z, coefficients))
    model = assembly.Model(grid, terms)

    def iterate(r, z, model, tol, max_iter, it, shift):
        return newton_loop.iterate(r, z, model, tol, max_iter, it, shift,
                                   newton_loop.model_derivatives, newton_loop.model_energy)

    return iterate, model, model.energy


def minimize(grid: Grid, r0: np.ndarray, z0: np.ndarray, *, tol: float = 1e-10,
             max_iter: int = 200, terms=None, prepared=None) -> NewtonResult:
    """Minimize the reduced energy from an admissible start (r0, z0), dR units. ``terms``:
    the energy terms (default: ``terms.ALL_TERMS``; variants and added effects go here);
    ``prepared``: ``prepare(grid, terms)`` computed before (then ``terms`` is not used)."""
    iterate, model, energy = prepare(grid, terms) if prepared is None else prepared
    r = np.array(r0, dtype=float)
    u = np.maximum(np.asarray(z0[:-1], float) - np.asarray(z0[1:], float), 0.0)
    u[0] = 0.0
    z = heights(u)
    if not np.isfinite(energy(r, z)):
        return NewtonResult(r, z, np.inf, np.inf, 0, False, None, "start is outside the energy's domain")
    shift, it, second_order, escapes = 0.0, 0, None, 0
    while True:
        r, z, E, residual, it, shift, status, hb, free = iterate(
            r, z, model, float(tol), int(max_iter), it, shift)
        if status == newton_loop.BUDGET:
            message = "iteration budget exhausted"
            break
        if status == newton_loop.LINE_SEARCH_FAILED:
            message = "line search failed"
            break
        if status == newton_loop.STALLED:
            message = "certificate stalled at its round-off floor, above the tolerance"
            break
        second_order = status == newton_loop.MINIMUM
        if second_order or escapes >= MAX_ESCAPES:
            message = "converged" if second_order else "converged to a saddle point"
            break
        escaped = _escape(energy, grid.n_inside, r, z, E, *newton_loop.escape_system(hb, free))
        if escaped is None:
            message = "converged to a saddle point (no descent along negative curvature)"
            break
        r, z = escaped
        escapes += 1
    return NewtonResult(r, z, float(E), float(residual), it, residual <= tol, second_order,
                        message)
