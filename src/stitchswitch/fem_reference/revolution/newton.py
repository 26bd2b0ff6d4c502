"""Newton's method for the shell's energy, with negative-curvature handling and a line search.

The free Hessian is small (a few hundred unknowns) and is factorized dense after Jacobi
scaling D^-1 H D^-1: its Cholesky factor gives the Newton step where it is positive definite;
elsewhere (near a buckling point or a saddle) it is shifted by 2 |mu_min| (mu_min its lowest
eigenvalue), so every step descends and saddles are left along negative curvature. The step is
backtracked until the energy satisfies Armijo's condition; a trial outside the energy's domain
(a zero radius or stretch) has energy +inf and is backtracked too. Converged: the max-norm of
the free gradient is at most ``tol``. The certificate of a strict local minimum is the lowest
eigenvalue of the scaled free Hessian at the result (> ``MIN_EIGENVALUE``).
"""
from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np
from scipy.linalg import LinAlgError, cho_factor, cho_solve, eigh

from stitchswitch.blas import one_thread

#: The scaled Hessian's lowest eigenvalue above which a converged state is a strict minimum:
#: beyond the round-off of a scaled Hessian with entries of order one (its soft modes, slack
#: fabric resisting with the compressive ratio c ~ 0.005, sit at 1e-12 to 1e-10).
MIN_EIGENVALUE = 1e-13
DEFAULT_TOL = 1e-8


@dataclass(frozen=True)
class NewtonResult:
    y: np.ndarray
    energy: float
    residual: float
    converged: bool
    iterations: int
    solve_s: float


def _scaled(problem, y):
    E, g, H = problem.derivatives(y)
    f = problem.free
    Hf = H[f][:, f].toarray()
    d = np.abs(np.diag(Hf))
    D = np.sqrt(np.maximum(d, 1e-12 * max(float(d.max()), 1e-300)))
    return E, g[f], Hf / np.outer(D, D), D


def lowest_eigenvalue(problem, y) -> float:
    """The lowest eigenvalue of the Jacobi-scaled free Hessian at ``y``."""
    return lowest_mode(problem, y)[0]


def lowest_mode(problem, y):
    """(lowest eigenvalue, its eigenvector in the unknowns, unscaled) of the Jacobi-scaled free
    Hessian at ``y``."""
    with one_thread():
        _, _, A, D = _scaled(problem, y)
        w, V = eigh(A, subset_by_index=[0, 0])
    v = np.zeros(y.size)
    v[problem.free] = V[:, 0] / D
    return float(w[0]), v


def _direction(A, gs):
    try:
        return cho_solve(cho_factor(A, lower=True, check_finite=False), -gs)
    except LinAlgError:
        mu = float(eigh(A, eigvals_only=True, subset_by_index=[0, 0])[0])
        shift = max(-2.0 * mu, 0.0) + 1e-10
        n = A.shape[0]
        while True:
            try:
                return cho_solve(cho_factor(A + shift * np.eye(n), lower=True, check_finite=False), -gs)
            except LinAlgError:
                shift *= 10.0


def minimize(problem, y0, *, tol: float = DEFAULT_TOL, max_iter: int = 200) -> NewtonResult:
    """A local minimizer of ``problem`` from ``y0`` (fixed unknowns keep their values); one BLAS
    thread (the dense factorizations are small)."""
    with one_thread():
        return _minimize(problem, y0, tol, max_iter)


def _minimize(problem, y0, tol, max_iter) -> NewtonResult:
    t0 = time.perf_counter()
    y = np.array(y0, dtype=float)
    free = problem.free
    it, residual = 0, np.inf
    E = problem.energy(y)
    if not np.isfinite(E):
        return NewtonResult(y, E, np.inf, False, 0, time.perf_counter() - t0)
    while True:
        E, gf, A, D = _scaled(problem, y)
        residual = float(np.max(np.abs(gf)))
        if residual <= tol or it >= max_iter:
            break
        it += 1
        gs = gf / D
        step = _direction(A, gs)
        slope = float(gs @ step)
        d = step / D
        alpha, accepted = 1.0, False
        for _ in range(60):
            trial = y.copy()
            trial[free] += alpha * d
            E_new = problem.energy(trial)
            if E_new <= E + 1e-4 * alpha * slope or (
                    np.isfinite(E_new) and -slope <= 1e-14 * max(abs(E), 1.0)
                    and E_new <= E + 1e-13 * max(abs(E), 1.0)):
                accepted = True
                break
            alpha *= 0.5
        if not accepted:
            break
        y = trial
    return NewtonResult(y, float(E), residual, residual <= tol, it, time.perf_counter() - t0)
