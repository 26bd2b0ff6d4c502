"""Newton's method for the shell's energy, with negative-curvature handling and a line search.

The free Hessian is small (a few hundred unknowns) and is factorized dense after Jacobi
scaling D^-1 H D^-1: its Cholesky factor gives the Newton step where it is positive definite;
elsewhere (near a buckling point or a saddle) it is shifted by 2 |mu_min| (mu_min its lowest
eigenvalue), so every step descends and saddles are left along negative curvature. The step is
backtracked until the energy satisfies Armijo's condition; a trial outside the energy's domain
(a zero radius or stretch) has energy +inf and is backtracked too. Converged: the max-norm of
the free gradient is at most ``tol``. The certificate of a strict local minimum is the lowest
eigenvalue of the scaled free Hessian at the result (> ``MIN_EIGENVALUE``); where that
eigenvalue is within the round-off band (|mu| <= ``MIN_EIGENVALUE``) and the next one is above
it, the energy's second difference along the lowest mode (``mode_curvature``) decides
(``solve.ShellState.certified``).
"""
from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np
from scipy.linalg import LinAlgError, cho_factor, cho_solve, eigh

from stitchswitch.blas import one_thread

#: The scaled Hessian's lowest eigenvalue above which a converged state is a strict minimum:
#: beyond the round-off of a scaled Hessian with entries of order one. Below it in magnitude
#: (the flat states' vertical modes measure 1e-15 to 1e-10, their sign set by round-off)
#: ``resolved_curvature`` decides.
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
    w, V = lowest_modes(problem, y, 1)
    return float(w[0]), V[0]


def lowest_modes(problem, y, k: int = 2):
    """The ``k`` lowest eigenvalues of the Jacobi-scaled free Hessian at ``y`` (ascending) and
    their eigenvectors in the unknowns, unscaled (rows)."""
    with one_thread():
        _, _, A, D = _scaled(problem, y)
        w, V = eigh(A, subset_by_index=[0, k - 1])
    out = np.zeros((k, y.size))
    out[:, problem.free] = (V / D[:, None]).T
    return w, out


def mode_curvature(problem, y, v, amplitude_mm: float, energy: float | None = None) -> float:
    """The energy's central second difference along ``v`` (scaled to max-norm 1) at
    ``amplitude_mm``: E(y + a v) + E(y - a v) - 2 E(y), in units of E (``energy``: E(y), if
    already known).

    Along the softest mode the assembled Hessian cannot resolve the curvature when its scaled
    eigenvalue is at the eigensolver's round-off (about sqrt(n) eps |A|, where a few stiff
    unknowns dominate the Jacobi scaling); the energy, evaluated from the fields, resolves it to
    about eps |E| / a^2."""
    v = v / max(float(np.max(np.abs(v))), 1e-300)
    E0 = problem.energy(y) if energy is None else energy
    return float(problem.energy(y + amplitude_mm * v) + problem.energy(y - amplitude_mm * v) - 2.0 * E0)


#: How far the second differences at amplitudes a and a / 10 may depart from the quadratic
#: ratio 100 for the curvature to count as resolved.
QUADRATIC_TOLERANCE = 0.05


def resolved_curvature(problem, y, v, amplitude_mm: float) -> bool:
    """Whether the energy's curvature along ``v`` is positive and resolved: ``mode_curvature``
    at ``amplitude_mm`` / 10 is above the energy's round-off (64 eps |E|), and the one at
    ``amplitude_mm`` is 100 times it to ``QUADRATIC_TOLERANCE`` (the quadratic regime, so that
    a higher-order rise cannot hide a negative curvature)."""
    E0 = problem.energy(y)
    floor = 64.0 * np.finfo(float).eps * max(abs(E0), 1.0)
    big = mode_curvature(problem, y, v, amplitude_mm, E0)
    small = mode_curvature(problem, y, v, 0.1 * amplitude_mm, E0)
    if not (np.isfinite(big) and np.isfinite(small) and small > floor):
        return False
    return bool(abs(big / (100.0 * small) - 1.0) <= QUADRATIC_TOLERANCE)


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
