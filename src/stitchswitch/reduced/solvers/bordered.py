"""The restricted Newton system as a bordered band: the heights of long merged z groups are
numbered last, so a flat stretch of held drops does not widen the band.

Holding a run of drops at zero merges its nodes into one z group whose single height couples
to the r of every node in it. Numbered in place (``step.reduced_indices``), that variable
widens the band to the run's length, and the Cholesky factor fills the whole triangle between
the group's first r and its height (milliseconds per factor for a run of ~100 nodes, in about
a third of the iterations of the benchmark designs). Here every group of more than
``MAX_BAND_SPAN`` nodes is a border variable, numbered after all the others: the matrix is

    [[A, B^T], [B, C]]

with A banded (the r's and the short groups' heights; half-width at most ~7 + 2
``MAX_BAND_SPAN``), B dense m x n_band and C dense m x m for m border groups. It is factored by
block elimination: A = L D L^T (``banded.factor_rows``, L unit lower), Y = L^-1 B^T, the Schur
complement S = C - Y D^-1 Y^T = Ls Ls^T, and solved with two triangular sweeps each side. The matrix is
positive definite iff A and S are, so ``info`` answers the same question as a Cholesky of the
whole matrix. The direction equals the in-place numbering's to round-off
(tests/test_bordered.py compares both with dense linear algebra).
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit

from stitchswitch.reduced.solvers.banded import (
    CONTRACT,
    backward_rows,
    envelope_rows,
    factor_envelope,
    forward_rows,
)

#: A z group of more nodes than this is a border variable.
MAX_BAND_SPAN = 4


@njit(cache=True)
def indices(n, free_drop):
    """(dof_map, n_band, m): every interleaved dof's variable (-1: fixed). The groups and the
    gauge are ``step.reduced_indices``'s; variables are numbered node by node as there, except
    the height of a group of more than ``MAX_BAND_SPAN`` nodes, which is n_band + k for the
    k-th such group from the axis."""
    group = np.zeros(n, dtype=np.int64)
    for i in range(1, n):
        group[i] = group[i - 1] + (1 if free_drop[i - 1] else 0)
    n_groups = group[n - 1] + 1
    size = np.zeros(n_groups, dtype=np.int64)
    for i in range(n):
        size[group[i]] += 1
    gauge = group[n - 1]
    m = 0
    for k in range(gauge):
        if size[k] > MAX_BAND_SPAN:
            m += 1
    n_band = (n - 1) + (gauge - m)
    z_var = np.full(n_groups, -1, dtype=np.int64)
    dof_map = np.empty(2 * n, dtype=np.int64)
    count, border = 0, n_band
    for i in range(n):
        dof_map[2 * i] = -1 if i == 0 else count
        if i > 0:
            count += 1
        k = group[i]
        if (i == 0 or free_drop[i - 1]) and k != gauge:
            if size[k] > MAX_BAND_SPAN:
                z_var[k] = border
                border += 1
            else:
                z_var[k] = count
                count += 1
    for i in range(n):
        dof_map[2 * i + 1] = z_var[group[i]]
    return dof_map, n_band, m


@njit(cache=True)
def restrict(hb, dof_map, n_band, m):
    """(At, B, C): P^T H P for H given as a lower band ``hb`` (global dofs) and P the 0/1
    matrix that maps variable ``dof_map[a]`` to global dof a (-1: fixed), split into the band
    rows ``At`` of the band variables (``At[j, k] = A[j + k, j]``, ``banded``'s row layout), the
    border rows B
    (m, n_band) and the border block C (m, m). Several global dofs may share one variable
    (merged z groups): their coupling then counts twice on the diagonal. With m = 0 (the
    node-by-node numbering of ``step.reduced_indices``, n_band = all variables) ``At`` is the
    whole restricted band."""
    kmax, n = hb.shape
    band = np.empty(n, dtype=np.int64)     # each dof's band variable, -1 for none
    for j in range(n):
        band[j] = dof_map[j] if dof_map[j] < n_band else -1
    bw = 0                                 # the widest coupling of two band variables
    for k in range(1, kmax):               # (diagonal by diagonal: branch-free, vectorized)
        for j in range(n - k):
            J, I = band[j], band[j + k]
            d = I - J if I > J else J - I
            bw = max(bw, d if (I >= 0) & (J >= 0) else 0)
    At = np.zeros((n_band, bw + 1))
    B = np.zeros((m, n_band))
    C = np.zeros((m, m))
    # entry by entry in the same order (j, then k) whatever the destination, so every sum
    # is formed in one fixed order; the band columns and the border columns apart
    for j in range(n):
        J = dof_map[j]
        if J < 0:
            continue
        kend = min(kmax, n - j)
        if J < n_band:
            for k in range(kend):
                I = dof_map[j + k]
                if I < 0:
                    continue
                v = hb[k, j]
                if I >= n_band:
                    B[I - n_band, J] += v
                elif I > J:
                    At[J, I - J] += v
                elif I < J:
                    At[I, J - I] += v
                else:
                    At[I, 0] += v if k == 0 else 2.0 * v
        else:
            for k in range(kend):
                I = dof_map[j + k]
                if I < 0:
                    continue
                v = hb[k, j]
                if I == J:
                    C[I - n_band, I - n_band] += v if k == 0 else 2.0 * v
                elif I >= n_band:
                    C[I - n_band, J - n_band] += v
                    C[J - n_band, I - n_band] += v
                else:
                    B[J - n_band, I] += v
    return At, B, C


@njit(cache=True, fastmath=CONTRACT)
def factor(At, B, C, shift):
    """(Lt, ends, Y, Ls, first, info) for [[A, B^T], [B, C]] + shift I: the band factor
    A = L D L^T (``banded.factor_rows``: rows and envelope), Y = L^-1 B^T by rows (m, n_band)
    with each row's first nonzero ``first``, the lower Cholesky factor Ls of the Schur
    complement S = C - Y D^-1 Y^T and info: 0 on success, else nonzero (not positive
    definite)."""
    return factor_with(At, envelope_rows(At), B, C, shift)


@njit(cache=True, fastmath=CONTRACT)
def factor_with(At, ends, B, C, shift):
    """``factor`` with the envelope ``ends`` of ``At`` (``banded.envelope_rows``) given: the
    shift search of a Newton step finds it once for all its shifts."""
    Lt, ends, info = factor_envelope(At, ends, shift)
    m, n_band = B.shape
    Y = B.copy()
    first = np.full(m, n_band, dtype=np.int64)
    Ls = C.copy()
    if info != 0:
        return Lt, ends, Y, Ls, first, info
    for k in range(m):
        for j in range(n_band):
            if Y[k, j] != 0.0:
                first[k] = j
                break
        forward_rows(Lt, ends, Y[k], first[k])
    for k in range(m):
        Ls[k, k] += shift
        for q in range(k + 1):
            s = 0.0
            for j in range(max(first[k], first[q]), n_band):
                s += Y[k, j] * Y[q, j] * Lt[j, 0]
            Ls[k, q] -= s
    for j in range(m):                      # dense Cholesky of S, lower triangle in place
        d = Ls[j, j]
        for p in range(j):
            d -= Ls[j, p] * Ls[j, p]
        if not d > 0.0:
            return Lt, ends, Y, Ls, first, n_band + j + 1
        d = math.sqrt(d)
        Ls[j, j] = d
        for i in range(j + 1, m):
            s = Ls[i, j]
            for p in range(j):
                s -= Ls[i, p] * Ls[j, p]
            Ls[i, j] = s / d
    return Lt, ends, Y, Ls, first, 0


@njit(cache=True, fastmath=CONTRACT)
def solve(Lt, ends, Y, Ls, first, rhs):
    """Solve the system factored by ``factor`` for ``rhs`` (n_band + m,)."""
    n_band, m = Lt.shape[0], Ls.shape[0]
    x = rhs.copy()
    xb = x[:n_band]
    forward_rows(Lt, ends, xb, 0)           # x_b <- L^-1 rhs_b
    for k in range(m):                      # x_c <- Ls^-1 (rhs_c - Y D^-1 x_b)
        s = x[n_band + k]
        for j in range(first[k], n_band):
            s -= Y[k, j] * (xb[j] * Lt[j, 0])
        for p in range(k):
            s -= Ls[k, p] * x[n_band + p]
        x[n_band + k] = s / Ls[k, k]
    for k in range(m - 1, -1, -1):          # x_c <- Ls^-T x_c
        s = x[n_band + k]
        for p in range(k + 1, m):
            s -= Ls[p, k] * x[n_band + p]
        x[n_band + k] = s / Ls[k, k]
    for k in range(m):                      # x_b <- L^-T D^-1 (x_b - Y^T x_c)
        t = x[n_band + k]
        for j in range(first[k], n_band):
            xb[j] -= Y[k, j] * t
    backward_rows(Lt, ends, xb)
    return x
