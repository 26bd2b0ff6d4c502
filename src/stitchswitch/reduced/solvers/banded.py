"""Banded linear algebra for the Newton solver: a positive-definiteness-checking factor and
solve, and the lowest mode (the restriction of the Hessian to an active set's variables is
``bordered.restrict``).

The solver keeps bands as rows (``*_rows``: ``At[j, k] = A[j + k, j]``, C order, so each band
column is contiguous and nothing is copied or transposed between restriction, factor and
solve); the functions without the suffix take and return LAPACK's lower band storage
(``ab[k, j] = A[j + k, j]``), the layout of scipy's banded routines, for the tests.

The factorization is compiled (``factor_rows``, ``solve_rows``) rather than LAPACK's
``dpbtrf``/``dpbtrs`` through scipy: the band is at most a few entries wide and ~600 long, so
the factorization itself costs microseconds and a call through Python cost more than the work;
compiled, the Newton loop (``newton_loop``) calls it without leaving numba. It is ``dpbtf2``'s
algorithm (the unblocked right-looking elimination LAPACK uses for narrow bands) in root-free
form, L D L^T with L unit lower triangular: no square root between one pivot and the next, so
the chain of dependent operations that bounds its speed on these narrow bands is shorter.
It reports failure the same way: info = j + 1 when the leading minor of order j + 1 is not
positive definite (tests/test_banded.py compares the Cholesky factor ``factor`` forms from it
with scipy's LAPACK). A long merged z group makes the band wide but only the group's columns
long; the factorization and the solve stop each column at its ``envelope``, which skips only
updates by exact zeros (tests/test_banded_envelope.py: the full-band loops' factor, bit for
bit)."""
from __future__ import annotations

import math

import numpy as np
from numba import njit

#: LLVM may fuse a*b + c into one rounding (FMA) in the factorization, as the optimized BLAS
#: kernels behind LAPACK do (one rounding less, and a shorter chain of dependent operations).
#: No other fast-math relaxation is allowed: the results do not depend on the compiler's
#: reassociation.
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
    """(Ft, ends, info): the root-free (L D L^T) factor of A + shift I as band rows (``At``
    from ``bordered.restrict``, not modified), its ``envelope_rows`` and LAPACK's info: 0 on
    success, j + 1 if the leading minor of order j + 1 is not positive definite (then the
    factor is incomplete). ``Ft[j, 0] = 1 / d_j`` and ``Ft[j, p] = L[j + p, j]`` (L unit lower
    triangular): A + shift I = L D L^T.

    Each column is eliminated only down to its envelope: below it the factor is exactly zero,
    so the operations skipped would add zeros (the factor is the full band's elimination bit
    for bit, at a cost that grows with the long columns only, not with the band's widest
    column)."""
    return factor_envelope(At, envelope_rows(At), shift)


@njit(cache=True, fastmath=CONTRACT)
def factor_envelope(At, ends, shift):
    """``factor_rows`` with the envelope ``ends`` of ``At`` given: a shift changes only the
    diagonal, so a search over shifts finds the envelope once.

    The right-looking elimination of ``dpbtf2`` without its square roots: column j's pivot
    d_j is the updated diagonal, its multipliers are the column times 1 / d_j, and the
    trailing block is updated with the unscaled column times the multiplier. The chain of
    dependent operations from one pivot to the next is then a reciprocal, a product and an
    update (Cholesky adds a square root and a second product to it), which makes the factor
    about a third faster on the solver's narrow bands; positive definiteness is decided by
    the same test (every pivot > 0)."""
    n = At.shape[0]
    Ft = At.copy()
    for j in range(n):
        Ft[j, 0] += shift
    for j in range(n):
        djj = Ft[j, 0]
        if not djj > 0.0:                  # also catches NaN, as dpbtf2 does
            return Ft, ends, j + 1
        inv = 1.0 / djj
        Ft[j, 0] = inv
        kn = ends[j]
        for q in range(1, kn + 1):         # rank-1 update of the trailing block
            t = -Ft[j, q] * inv            # minus the multiplier L[j + q, j]
            for p in range(q, kn + 1):     # entries p >= q of the column: still unscaled
                Ft[j + q, p - q] += Ft[j, p] * t
            Ft[j, q] = -t
    return Ft, ends, 0


@njit(cache=True, fastmath=CONTRACT)
def forward_rows(Ft, ends, x, start):
    """x <- L^-1 x in place (L unit lower) for a factor from ``factor_rows``, from row
    ``start`` on (the entries of x before it are zero)."""
    for j in range(start, Ft.shape[0]):
        t = x[j]
        for p in range(1, ends[j] + 1):
            x[j + p] -= t * Ft[j, p]


@njit(cache=True, fastmath=CONTRACT)
def backward_rows(Ft, ends, x):
    """x <- L^-T D^-1 x in place for a factor from ``factor_rows``. Each row's sum runs from
    the far end of the row, so the product with the unknown just solved comes last: the chain
    of dependent operations from one unknown to the next is one update and one product."""
    for j in range(Ft.shape[0] - 1, -1, -1):
        t = 0.0
        for p in range(ends[j], 0, -1):
            t += Ft[j, p] * x[j + p]
        x[j] = x[j] * Ft[j, 0] - t


@njit(cache=True, fastmath=CONTRACT)
def solve_rows(Ft, ends, rhs):
    """Solve (L D L^T) x = rhs with a factor from ``factor_rows`` (forward, then the scaled
    backward), each column only down to its envelope ``ends`` (the factor is zero below it)."""
    x = rhs.copy()
    forward_rows(Ft, ends, x, 0)
    backward_rows(Ft, ends, x)
    return x


@njit(cache=True)
def factor(ab, shift):
    """The Cholesky factor of ab + shift I in LAPACK's lower band storage (``ab[k, j] =
    A[j + k, j]``), from ``factor_rows``: L_chol = L sqrt(D); and info. An incomplete factor
    (info > 0) is converted up to the failed column."""
    Ft, _, info = factor_rows(np.ascontiguousarray(ab.T), shift)
    done = Ft.shape[0] if info == 0 else info - 1
    for j in range(done):
        s = 1.0 / math.sqrt(Ft[j, 0])      # sqrt(d_j)
        Ft[j, 0] = s
        for p in range(1, Ft.shape[1]):
            Ft[j, p] *= s
    return Ft.T, info


@njit(cache=True)
def solve_factored(L, rhs):
    """Solve (L L^T) x = rhs with a Cholesky factor from ``factor`` (as ``solve_rows``, after
    writing it back in root-free form)."""
    Ft = np.ascontiguousarray(L.T)
    for j in range(Ft.shape[0]):
        s = Ft[j, 0]
        Ft[j, 0] = 1.0 / (s * s)
        for p in range(1, Ft.shape[1]):
            Ft[j, p] /= s
    return solve_rows(Ft, envelope_rows(Ft), rhs)


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
    """``lowest_mode``: bisection on sigma with the factor's test (A - sigma I is positive
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
    At = np.ascontiguousarray(ab.T)
    ends = envelope_rows(At)
    if factor_envelope(At, ends, -hi)[2] == 0:
        lo = hi
    while hi - lo > 1e-13 * scale:
        mid = 0.5 * (lo + hi)
        if factor_envelope(At, ends, -mid)[2] == 0:
            lo = mid
        else:
            hi = mid
    Ft = factor_envelope(At, ends, -lo)[0]
    x = np.empty(n)
    for i in range(n):
        x[i] = 1.0 + 0.5 * math.sin(1.0 + i)       # deterministic, not orthogonal to a mode
    for _ in range(4):
        x = solve_rows(Ft, ends, x)
        x /= math.sqrt(np.sum(x * x))
    return np.sum(x * _band_matvec(ab, x)), x


def lowest_mode(ab: np.ndarray) -> tuple[float, np.ndarray]:
    """Smallest eigenvalue and its unit eigenvector of a symmetric lower-banded matrix
    (``lowest_mode_compiled``: LAPACK's dsbevx through scipy formed a dense n x n transform and
    cost 6-20 ms per saddle escape for ~600 unknowns)."""
    lam, v = lowest_mode_compiled(np.ascontiguousarray(ab, dtype=float))
    return float(lam), v
