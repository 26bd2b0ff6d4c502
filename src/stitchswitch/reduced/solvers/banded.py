"""Banded linear algebra for the Newton solver: a positive-definiteness-checking Cholesky
solve and the lowest mode (the restriction of the Hessian to an active set's variables is
``bordered.restrict``).

The solver keeps bands as rows (``*_rows``: ``At[j, k] = A[j + k, j]``, C order, so each band
column is contiguous and nothing is copied or transposed between restriction, factor and
solve); the functions without the suffix take and return LAPACK's lower band storage
(``ab[k, j] = A[j + k, j]``), the layout of scipy's banded routines, for the tests and the
lowest mode.

The factorization is compiled (``factor``, ``solve_factored``) rather than LAPACK's
``dpbtrf``/``dpbtrs`` through scipy: the band is at most a few entries wide and ~600 long, so
the factorization itself costs microseconds and a call through Python cost more than the work;
compiled, the Newton loop (``newton_loop``) calls it without leaving numba. It is ``dpbtf2``'s
algorithm (the unblocked right-looking Cholesky LAPACK uses for narrow bands) and reports
failure the same way: info = j + 1 when the leading minor of order j + 1 is not positive
definite (tests/test_banded.py compares it with scipy's LAPACK). A long merged z group makes
the band wide but only the group's columns long; the factorization and the solve stop each
column at its ``envelope``, which skips only updates by exact zeros (tests/test_banded_envelope.py:
the full-band loops' factor, bit for bit)."""
from __future__ import annotations

import math

import numpy as np
from numba import njit

#: LLVM may fuse a*b + c into one rounding (FMA) in the factorization, as the optimized BLAS
#: kernels behind LAPACK do: then the factor is bit for bit LAPACK's on this machine, not just
#: equal to round-off, and the solver's iterates follow the LAPACK solver's. No other
#: fast-math relaxation is allowed.
CONTRACT = {"contract"}


@njit(cache=True)
def envelope_rows(At):
    """Per column j, how many subdiagonal entries of its Cholesky factor can be nonzero: the
    last nonzero of column j of A, or the fill of an earlier column reaching below it
    (Cholesky fills a column only between its diagonal and the lowest row an earlier column
    reaches). A long merged z group makes the band wide (its height couples to every r of the
    group) but only its own columns long; every other column keeps a few entries. ``At``: band
    rows (``bordered.restrict``)."""
    n, kd = At.shape[0], At.shape[1] - 1
    ends = np.empty(n, dtype=np.int64)
    reach = -1                             # lowest row reached by an earlier column
    for j in range(n):
        h = 0
        for k in range(min(kd, n - 1 - j), 0, -1):
            if At[j, k] != 0.0:            # NaN counts as nonzero
                h = k
                break
        reach = max(reach, j + h)
        ends[j] = reach - j
    return ends


@njit(cache=True)
def envelope(ab):
    """``envelope_rows`` of a band in LAPACK's lower band storage."""
    return envelope_rows(np.ascontiguousarray(ab.T))


@njit(cache=True, fastmath=CONTRACT)
def factor_rows(At, shift):
    """(Lt, ends, info): the lower banded Cholesky factor of A + shift I as band rows (``At``
    from ``bordered.restrict``, not modified), its ``envelope_rows`` and LAPACK's info: 0 on
    success, j + 1 if the leading minor of order j + 1 is not positive definite (then the
    factor is incomplete).

    Each column is eliminated only down to its envelope: below it the factor is exactly zero,
    so the operations skipped would add zeros (the factor is dpbtf2's bit for bit, at a cost
    that grows with the long columns only, not with the band's widest column)."""
    return factor_envelope(At, envelope_rows(At), shift)


@njit(cache=True, fastmath=CONTRACT)
def factor_envelope(At, ends, shift):
    """``factor_rows`` with the envelope ``ends`` of ``At`` given: a shift changes only the
    diagonal, so a search over shifts finds the envelope once."""
    n = At.shape[0]
    Lt = At.copy()
    for j in range(n):
        Lt[j, 0] += shift
    for j in range(n):
        ajj = Lt[j, 0]
        if not ajj > 0.0:                  # also catches NaN, as dpbtf2 does
            return Lt, ends, j + 1
        ajj = math.sqrt(ajj)
        Lt[j, 0] = ajj
        kn = ends[j]
        inv = 1.0 / ajj
        for p in range(1, kn + 1):
            Lt[j, p] *= inv
        for q in range(1, kn + 1):         # rank-1 update of the trailing block (dsyr)
            t = -Lt[j, q]
            for p in range(q, kn + 1):
                Lt[j + q, p - q] += Lt[j, p] * t
    return Lt, ends, 0


@njit(cache=True, fastmath=CONTRACT)
def forward_rows(Lt, ends, x, start):
    """x <- L^-1 x in place for a factor from ``factor_rows``, from row ``start`` on (the
    entries of x before it are zero)."""
    for j in range(start, Lt.shape[0]):
        t = x[j] * (1.0 / Lt[j, 0])        # the reciprocal does not wait for x: no division
        x[j] = t                           # in the chain of dependent updates
        for p in range(1, ends[j] + 1):
            x[j + p] -= t * Lt[j, p]


@njit(cache=True, fastmath=CONTRACT)
def backward_rows(Lt, ends, x):
    """x <- L^-T x in place for a factor from ``factor_rows``."""
    for j in range(Lt.shape[0] - 1, -1, -1):
        t = 0.0
        for p in range(1, ends[j] + 1):
            t += Lt[j, p] * x[j + p]
        x[j] = (x[j] - t) * (1.0 / Lt[j, 0])


@njit(cache=True, fastmath=CONTRACT)
def solve_rows(Lt, ends, rhs):
    """Solve (L L^T) x = rhs with a factor from ``factor_rows`` (dpbtrs: forward, then
    backward), each column only down to its envelope ``ends`` (the factor is zero below it)."""
    x = rhs.copy()
    forward_rows(Lt, ends, x, 0)
    backward_rows(Lt, ends, x)
    return x


@njit(cache=True)
def factor(ab, shift):
    """``factor_rows`` in LAPACK's lower band storage (``ab[k, j] = A[j + k, j]``): the factor
    in the same storage (a view of the rows) and info."""
    Lt, _, info = factor_rows(np.ascontiguousarray(ab.T), shift)
    return Lt.T, info


@njit(cache=True)
def solve_factored(L, rhs):
    """Solve (L L^T) x = rhs with a factor from ``factor`` (``solve_rows``)."""
    Lt = np.ascontiguousarray(L.T)
    return solve_rows(Lt, envelope_rows(Lt), rhs)


def cholesky(ab: np.ndarray, shift: float = 0.0):
    """Lower banded Cholesky factor of ab + shift I (``factor``), or None if that is not
    positive definite."""
    L, info = factor(np.ascontiguousarray(ab, dtype=float), float(shift))
    return L if info == 0 else None


def solve(factor_: np.ndarray, rhs: np.ndarray) -> np.ndarray:
    """Solve with a factor from ``cholesky``."""
    return solve_factored(factor_, np.ascontiguousarray(rhs, dtype=float))


@njit(cache=True)
def _band_matvec(ab, x):
    kd, n = ab.shape[0] - 1, ab.shape[1]
    y = np.zeros(n)
    for j in range(n):
        y[j] += ab[0, j] * x[j]
        for k in range(1, min(kd, n - 1 - j) + 1):
            y[j + k] += ab[k, j] * x[j]
            y[j] += ab[k, j] * x[j + k]
    return y


@njit(cache=True)
def lowest_mode_compiled(ab):
    """``lowest_mode``: bisection on sigma with the Cholesky test (A - sigma I is positive
    definite iff sigma < lambda_min), from a Gershgorin lower bound up to 0, to a width of
    1e-13 times the largest entry; then inverse iteration with the last definite shift (a few
    solves: the shift is within that width of lambda_min) and the Rayleigh quotient."""
    kd, n = ab.shape[0] - 1, ab.shape[1]
    scale, lo = 0.0, math.inf
    for i in range(n):
        off = 0.0
        for k in range(1, kd + 1):
            if i + k < n:
                off += abs(ab[k, i])
            if i - k >= 0:
                off += abs(ab[k, i - k])
        lo = min(lo, ab[0, i] - off)
        for k in range(kd + 1):
            scale = max(scale, abs(ab[k, i]))
    scale = scale if scale > 0.0 else 1.0
    lo = min(lo, 0.0) - 1e-3 * scale
    hi = 0.0
    if factor(ab, -hi)[1] == 0:
        lo = hi
    while hi - lo > 1e-13 * scale:
        mid = 0.5 * (lo + hi)
        if factor(ab, -mid)[1] == 0:
            lo = mid
        else:
            hi = mid
    L, info = factor(ab, -lo)
    x = np.empty(n)
    for i in range(n):
        x[i] = 1.0 + 0.5 * math.sin(1.0 + i)       # deterministic, not orthogonal to a mode
    for _ in range(4):
        x = solve_factored(L, x)
        x /= math.sqrt(np.sum(x * x))
    return np.sum(x * _band_matvec(ab, x)), x


def lowest_mode(ab: np.ndarray) -> tuple[float, np.ndarray]:
    """Smallest eigenvalue and its unit eigenvector of a symmetric lower-banded matrix
    (``lowest_mode_compiled``: LAPACK's dsbevx through scipy formed a dense n x n transform and
    cost 6-20 ms per saddle escape for ~600 unknowns)."""
    lam, v = lowest_mode_compiled(np.ascontiguousarray(ab, dtype=float))
    return float(lam), v
