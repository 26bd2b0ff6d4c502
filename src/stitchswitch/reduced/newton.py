"""Certified projected Newton method for the bound-constrained reduced problem.

Bertsekas' projected Newton method (SIAM J. Control Optim. 20, 1982) in the variables
x = (r_1..r_{N-1}, u_1..u_{N-2}) of ``constraints``:

1. The epsilon-active set A = {j : u_j <= eps, dE/du_j > 0}, eps = min(EPS_ACTIVE, residual),
   is held at u_j = 0. Holding u_j = 0 merges nodes j and j+1 into one z group, so the
   reduced Hessian in (r, group heights) stays banded: groups are runs of consecutive nodes.
2. The reduced Hessian is factored by banded Cholesky (LAPACK pbtrf). If it is not positive
   definite, a multiple of the identity is added and increased until it is (Nocedal & Wright,
   Alg. 3.3), so every step is a descent step; the last factorization tells whether the
   solution is a strict local minimum (``second_order``).
3. An Armijo backtracking search along the projection arc u <- max(u + a du, 0) keeps the
   iterate admissible (the energy is +inf outside its domain, so no node crosses the axis and
   no segment folds or collapses).

The result is certified by the max-norm of the projected gradient (``constraints.kkt_residual``);
``converged`` is True only when it is <= ``tol``.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.linalg import LinAlgError, cho_solve_banded, cholesky_banded

from stitchswitch.reduced import assembly
from stitchswitch.reduced.constraints import drop_gradient, kkt_residual, z_from_drops
from stitchswitch.reduced.discretization import Grid

EPS_ACTIVE = 0.0
ARMIJO = 1e-4
MAX_BACKTRACK = 60
SHIFT_FLOOR = 1e-10
RETRACT = True


@dataclass(frozen=True)
class NewtonResult:
    r: np.ndarray
    z: np.ndarray
    energy: float
    residual: float
    iterations: int
    converged: bool
    second_order: bool
    message: str


def _reduced_indices(n: int, free_drop: np.ndarray):
    """Map every interleaved dof to its reduced variable (-1: fixed).

    free_drop[j] (j = 0..N-2) tells whether u_j is free; a free drop starts a new z group.
    Variables are numbered node by node: r_i, then the group height when node i opens a group.
    The group holding node N-1 is the gauge (z = 0) and has no variable."""
    group = np.concatenate([[0], np.cumsum(free_drop)])            # group of each node
    opens = np.concatenate([[True], free_drop])                    # node opens its group
    gauge = group == group[-1]
    has_z = opens & ~gauge
    per_node = np.ones(n, dtype=int) + has_z
    per_node[0] -= 1                                               # r_0 is fixed
    start = np.concatenate([[0], np.cumsum(per_node)[:-1]])
    idx_r = np.where(np.arange(n) == 0, -1, start)
    z_var = np.full(group[-1] + 1, -1)
    z_var[group[opens & ~gauge]] = (start + (np.arange(n) > 0))[has_z]
    idx_z = z_var[group]
    dof_map = np.empty(2 * n, dtype=int)
    dof_map[0::2] = idx_r
    dof_map[1::2] = idx_z
    return dof_map, int(per_node.sum())


def _band(rows, cols, vals, dof_map, n_red):
    I, J = dof_map[rows], dof_map[cols]
    keep = (I >= 0) & (J >= 0) & (I >= J)
    I, J, v = I[keep], J[keep], vals[keep]
    bw = int(np.max(I - J)) if I.size else 0
    ab = np.bincount((I - J) * n_red + J, v, minlength=(bw + 1) * n_red).reshape(bw + 1, n_red)
    return ab


def _band_matvec(ab: np.ndarray, x: np.ndarray) -> np.ndarray:
    """y = A x for a symmetric matrix in lower banded storage."""
    y = ab[0] * x
    for k in range(1, ab.shape[0]):
        y[k:] += ab[k, :-k] * x[:-k]
        y[:-k] += ab[k, :-k] * x[k:]
    return y


class _Retraction:
    """Apply a Cartesian Newton step segment by segment in polar form.

    The step (dr, dz) is turned into increments of each segment's length and angle (to first
    order identical), and the new profile is rebuilt from the pole (r_0 = 0) and the gauge
    (z_{N-1} = 0). Rotating segments keep their length instead of stretching along the secant,
    which is what lets Newton follow the large rotations of the pop-up. Angles are kept in
    [-pi, 0], the sign constraint z' <= 0."""

    def __init__(self, r, z, dr, dz):
        self.vr, self.vz = np.diff(r), np.diff(z)
        self.l = np.hypot(self.vr, self.vz)
        self.phi = np.arctan2(self.vz, self.vr)
        self.phi[self.phi > 0] = np.where(self.phi[self.phi > 0] > np.pi / 2, -np.pi, 0.0)
        wr, wz = np.diff(dr), np.diff(dz)
        self.dl = (self.vr * wr + self.vz * wz) / self.l
        self.dphi = (self.vr * wz - self.vz * wr) / self.l ** 2

    def __call__(self, alpha):
        l = self.l + alpha * self.dl
        phi = np.clip(self.phi + alpha * self.dphi, -np.pi, 0.0)
        phi[0] = 0.0
        if np.any(l <= 0):
            return np.full(l.size + 1, np.nan), np.zeros(l.size + 1)
        r = np.concatenate([[0.0], np.cumsum(l * np.cos(phi))])
        u = -l * np.sin(phi)
        u[0] = 0.0
        return r, z_from_drops(np.maximum(u, 0.0))


def _factor(ab: np.ndarray, shift: float):
    """Banded Cholesky of ab + shift * I; returns the factor or None if not PD."""
    m = ab.copy()
    m[0] += shift
    try:
        return cholesky_banded(m, lower=True, check_finite=False)
    except LinAlgError:
        return None


def minimize(grid: Grid, r0: np.ndarray, z0: np.ndarray, *, tol: float = 1e-10,
             max_iter: int = 200) -> NewtonResult:
    """Minimize the reduced energy from an admissible start (r0, z0), dR units."""
    n = grid.n_nodes
    r = np.array(r0, dtype=float)
    u = np.maximum(np.asarray(z0[:-1], float) - np.asarray(z0[1:], float), 0.0)
    u[0] = 0.0
    z = z_from_drops(u)
    shift = 0.0
    it = 0
    residual = np.inf
    second_order = False
    message = "iteration budget exhausted"
    E = assembly.energy(r, z, grid)
    if not np.isfinite(E):
        return NewtonResult(r, z, E, np.inf, 0, False, False, "start is outside the energy's domain")
    while True:
        E, g, (rows, cols, vals) = assembly.derivatives(r, z, grid)
        g_r, g_z = g[0::2], g[1::2]
        residual = kkt_residual(g_r, g_z, u)
        g_u = drop_gradient(g_z)
        eps = min(EPS_ACTIVE, residual)
        free = ~((u <= eps) & (g_u > 0))
        free[0] = False
        dof_map, n_red = _reduced_indices(n, free)
        ab = _band(rows, cols, vals, dof_map, n_red)
        if residual <= tol:
            second_order = _factor(ab, 0.0) is not None
            message = "converged"
            break
        if it >= max_iter:
            break
        it += 1
        valid = dof_map >= 0
        g_red = np.bincount(dof_map[valid], g[valid], minlength=n_red)
        scale = float(np.mean(np.abs(ab[0]))) or 1.0
        shift = shift / 10.0 if shift > SHIFT_FLOOR * scale else 0.0
        factor = _factor(ab, shift)
        while factor is None:
            shift = max(10.0 * shift, SHIFT_FLOOR * scale)
            factor = _factor(ab, shift)
        d_red = cho_solve_banded((factor, True), -g_red, check_finite=False)
        d = np.where(valid, d_red[np.maximum(dof_map, 0)], 0.0)
        step = _Retraction(r, z, d[0::2], d[1::2]) if RETRACT else None
        alpha, accepted = 1.0, False
        for _ in range(MAX_BACKTRACK):
            if RETRACT:
                r_new, z_new = step(alpha)
            else:
                r_new = r + alpha * d[0::2]
                z_new = z_from_drops(np.maximum(u + alpha * (d[1::2][:-1] - d[1::2][1:]), 0.0))
            E_new = assembly.energy(r_new, z_new, grid)
            decrease = float(g[0::2] @ (r_new - r) + g[1::2] @ (z_new - z))
            if E_new <= E + ARMIJO * decrease:
                accepted = True
                break
            alpha *= 0.5
        if not accepted:
            message = "line search failed"
            break
        r, z = r_new, z_new
        u = np.maximum(z[:-1] - z[1:], 0.0)
        u[0] = 0.0
        z = z_from_drops(u)
    return NewtonResult(r, z, float(E), float(residual), it, residual <= tol, second_order, message)
