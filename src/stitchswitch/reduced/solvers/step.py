"""One projected Newton step's linear algebra, compiled: the certificate and the active set,
the reduced variables of that active set, and the shifted banded Newton direction.

In the variables x = (r_1..r_{N-1}, u_1..u_{N-2}) of ``constraints`` (u_j >= 0 the segment
drops), given the interleaved gradient g (2N,) and the drops u:

* ``stationarity``: the certificate max |x - P(x - grad E)| (``constraints.kkt_residual``) and
  the free drops (not in the active set A = {j : u_j = 0, dE/du_j > 0}; u_0 is never free);
* ``reduced_indices``: every interleaved dof's reduced variable (a held drop merges nodes j
  and j+1 into one z group), numbered node by node: the restricted Hessian is banded, wide
  where a long run of drops is held (the saddle escape's numbering; ``bordered.indices`` is
  the Newton step's);
* ``direction``: the Newton direction with the restricted Hessian (bordered band), shifted by
  a multiple of the identity that is increased tenfold until it is positive definite (Nocedal
  & Wright, Alg. 3.3), so every step descends. The search starts a decade below the last
  shift, or at the last shift when that one had to be raised (fewer failed factorizations).
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit

from stitchswitch.reduced.solvers import bordered

SHIFT_FLOOR = 1e-10      # smallest Hessian shift, relative to the mean diagonal


@njit(cache=True)
def stationarity(g, u):
    """(residual, free): the max-norm of the projected gradient (NaN if it is not finite) and
    the free drops (bool, N-1)."""
    free = np.empty(u.size, dtype=np.bool_)
    res, bad = 0.0, False
    for i in range(1, u.size + 1):
        v = abs(g[2 * i])
        bad |= v != v
        res = max(res, v)
    gu = 0.0
    for j in range(u.size):
        gu += g[2 * j + 1]                 # dE/du_j = sum_{i <= j} dE/dz_i
        free[j] = not (u[j] <= 0.0 and gu > 0.0)
        if j > 0:
            v = abs(min(u[j], gu))
            bad |= v != v
            res = max(res, v)
    free[0] = False
    return (math.nan if bad else res), free


@njit(cache=True)
def reduced_indices(n, free_drop):
    """(dof_map, n_red): the reduced variable of every interleaved dof (-1: fixed).

    free_drop[j] (j = 0..N-2) tells whether u_j is free; a free drop starts a new z group.
    Variables are numbered node by node: r_i, then the group height when node i opens a group.
    The group holding node N-1 is the gauge (z = 0) and has no variable; r_0 is fixed."""
    group = np.zeros(n, dtype=np.int64)
    for i in range(1, n):
        group[i] = group[i - 1] + (1 if free_drop[i - 1] else 0)
    z_var = np.full(group[n - 1] + 1, -1, dtype=np.int64)
    dof_map = np.empty(2 * n, dtype=np.int64)
    count = 0
    for i in range(n):
        has_z = (i == 0 or free_drop[i - 1]) and group[i] != group[n - 1]
        dof_map[2 * i] = -1 if i == 0 else count
        if i > 0:
            count += 1
        if has_z:
            z_var[group[i]] = count
            count += 1
    for i in range(n):
        dof_map[2 * i + 1] = z_var[group[i]]
    return dof_map, count


@njit(cache=True)
def direction(At, B, C, g, dof_map, shift, keep):
    """(d, shift, raised): the Newton direction in interleaved dofs (0 on fixed dofs) with the
    restricted Hessian in bordered form (``bordered``: band rows ``At``, border rows ``B``,
    border block ``C``, numbered by ``dof_map``) plus ``shift`` I, where ``shift`` starts at
    the previous step's shift divided by ten (0 below the floor), or at the previous shift
    itself if ``keep`` (the previous search had to raise its first trial: the Hessian needs
    about that shift still, and the trial a decade lower would fail again), and is raised
    tenfold until the factorization succeeds; ``raised`` tells whether it had to be. A
    Hessian no shift can make positive definite (not finite) gives a NaN direction, which the
    line search rejects."""
    n_band, m = At.shape[0], C.shape[0]
    n_red = n_band + m
    g_red = np.zeros(n_red)
    for a in range(g.size):
        if dof_map[a] >= 0:
            g_red[dof_map[a]] -= g[a]
    mean = 0.0
    for j in range(n_band):
        mean += abs(At[j, 0])
    for k in range(m):
        mean += abs(C[k, k])
    mean = mean / n_red if n_red > 0 else 0.0
    floor = SHIFT_FLOOR * (mean if mean != 0.0 else 1.0)
    if not keep:
        shift = shift / 10.0 if shift > floor else 0.0
    ends = bordered.envelope_rows(At)          # the same for every shift
    Lt, ends, Y, Ls, first, info = bordered.factor_with(At, ends, B, C, shift)
    raised = info != 0
    while info != 0:
        shift = max(10.0 * shift, floor)
        if not shift < math.inf:
            return np.full(g.size, math.nan), shift, True
        Lt, ends, Y, Ls, first, info = bordered.factor_with(At, ends, B, C, shift)
    x = bordered.solve(Lt, ends, Y, Ls, first, g_red)
    d = np.zeros(g.size)
    for a in range(g.size):
        if dof_map[a] >= 0:
            d[a] = x[dof_map[a]]
    return d, shift, raised
