"""Discrete-shell bending term (Eq. 4), the axisymmetric reduction of the hinge energy of
Jourdan et al. / Grinspun et al. (tan(theta/2) form).

Hinge i sits at node i+1 between segment vectors a = p_{i+1} - p_i and b = p_{i+2} - p_{i+1}:

    E_b = (1/N) sum_i w_b^(i) rho^2 / D * tan^2(theta/2),
    rho = r_{i+1},  D = rbar_i |a| + rbar_{i+1} |b|,  rbar_i = (r_i + r_{i+1}) / 2,
    tan(theta/2) = X / Y,  X = a x b = a_r b_z - a_z b_r,  Y = |a||b| + a.b.

rho^2 / D is (hinge circle length)^2 / (area of the two conical faces) up to 2 pi. Only the
meridional curvature is kept: the hoop curvature sin(phi)/r and Poisson coupling are dropped,
as in the paper. The energy is +inf for a full fold (Y <= 0) and for D <= 0.

The derivatives use the chain rule through the four scalars q = (rho, D, X, Y): each has a
simple gradient and Hessian in the six local dofs (r_i, z_i, r_{i+1}, z_{i+1}, r_{i+2}, z_{i+2}),
and F(q) = rho^2 X^2 / (D Y^2) has closed-form first and second partials.
"""
from __future__ import annotations

import numpy as np

STENCIL = 3
OFFSET = 0

# Constant Hessians in the six local dofs of the bilinear forms X = a x b and S = a.b,
# with a = (q2 - q0, q3 - q1) and b = (q4 - q2, q5 - q3).
_EA = np.array([[-1, 0, 1, 0, 0, 0], [0, -1, 0, 1, 0, 0]], dtype=float)
_EB = np.array([[0, 0, -1, 0, 1, 0], [0, 0, 0, -1, 0, 1]], dtype=float)
_M = np.array([[0.0, 1.0], [-1.0, 0.0]])
HESS_X = _EA.T @ _M @ _EB + _EB.T @ _M.T @ _EA
HESS_DOT = _EA.T @ _EB + _EB.T @ _EA
GRAD_MID0 = np.array([0.5, 0, 0.5, 0, 0, 0])     # rbar_i = (r_i + r_{i+1}) / 2
GRAD_MID1 = np.array([0, 0, 0.5, 0, 0.5, 0])


def _scalars(geo):
    ar, az, br, bz = geo.vr[:-1], geo.vz[:-1], geo.vr[1:], geo.vz[1:]
    la, lb = geo.l[:-1], geo.l[1:]
    r = geo.r
    m0, m1 = 0.5 * (r[:-2] + r[1:-1]), 0.5 * (r[1:-1] + r[2:])
    X = ar * bz - az * br
    Y = la * lb + ar * br + az * bz
    D = m0 * la + m1 * lb
    return r[1:-1], D, X, Y, (ar, az, br, bz, la, lb, m0, m1)


def energy(geo, grid) -> float:
    rho, D, X, Y, _ = _scalars(geo)
    if np.any(Y <= 0) or np.any(D <= 0):
        return np.inf
    return float(np.sum(grid.w_b * rho * rho * X * X / (D * Y * Y)) / grid.n_nodes)


def local(geo, grid, hessian: bool = True):
    rho, D, X, Y, (ar, az, br, bz, la, lb, m0, m1) = _scalars(geo)
    n = rho.size
    uar, uaz, ubr, ubz = ar / la, az / la, br / lb, bz / lb
    zero = np.zeros(n)
    # gradients (n, 6) of |a|, |b|, X, Y, D and rho in the local dofs
    dla = np.stack([-uar, -uaz, uar, uaz, zero, zero], axis=1)
    dlb = np.stack([zero, zero, -ubr, -ubz, ubr, ubz], axis=1)
    dX = np.stack([-bz, br, bz + az, -br - ar, -az, ar], axis=1)
    dY = lb[:, None] * dla + la[:, None] * dlb + np.stack([-br, -bz, br - ar, bz - az, ar, az], axis=1)
    dD = m0[:, None] * dla + m1[:, None] * dlb + la[:, None] * GRAD_MID0 + lb[:, None] * GRAD_MID1

    iD, iY = 1.0 / D, 1.0 / Y
    q = iD * iY * iY
    F = rho * rho * X * X * q
    Fr = 2 * rho * X * X * q
    FD = -F * iD
    FX = 2 * rho * rho * X * q
    FY = -2 * F * iY
    g = FD[:, None] * dD + FX[:, None] * dX + FY[:, None] * dY
    g[:, 2] += Fr
    c = grid.w_b / grid.n_nodes
    if not hessian:
        return c * F, c[:, None] * g, None

    # H = sum_kl F_kl (grad q_k)(grad q_l)^T + sum_k F_k Hess(q_k), q = (rho, D, X, Y); the
    # Hessians of D and Y contain rank-two products, gathered with the first term as V^T C V.
    V = np.empty((n, 8, 6))
    V[:, 0] = 0.0
    V[:, 0, 2] = 1.0
    V[:, 1], V[:, 2], V[:, 3] = dD, dX, dY
    V[:, 4], V[:, 5] = GRAD_MID0, GRAD_MID1
    V[:, 6], V[:, 7] = dla, dlb
    C = np.zeros((n, 8, 8))
    C[:, 0, 0] = 2 * X * X * q
    C[:, 0, 1] = C[:, 1, 0] = -Fr * iD
    C[:, 0, 2] = C[:, 2, 0] = 4 * rho * X * q
    C[:, 0, 3] = C[:, 3, 0] = -2 * Fr * iY
    C[:, 1, 1] = 2 * F * iD * iD
    C[:, 1, 2] = C[:, 2, 1] = -FX * iD
    C[:, 1, 3] = C[:, 3, 1] = 2 * F * iD * iY
    C[:, 2, 2] = 2 * rho * rho * q
    C[:, 2, 3] = C[:, 3, 2] = -2 * FX * iY
    C[:, 3, 3] = 6 * F * iY * iY
    C[:, 4, 6] = C[:, 6, 4] = FD          # Hess D contains grad(rbar_i) x grad|a| + transpose
    C[:, 5, 7] = C[:, 7, 5] = FD
    C[:, 6, 7] = C[:, 7, 6] = FY          # Hess Y contains grad|a| x grad|b| + transpose
    H = np.ascontiguousarray(V.transpose(0, 2, 1)) @ (C @ V)
    H += np.multiply.outer(FX, HESS_X)
    H += np.multiply.outer(FY, HESS_DOT)
    # remaining: (FD m0 + FY |b|) Hess|a| + (FD m1 + FY |a|) Hess|b|
    P = geo.length_projector()
    ca = (FD * m0 + FY * lb)[:, None, None] * P[:-1]
    cb = (FD * m1 + FY * la)[:, None, None] * P[1:]
    H[:, :2, :2] += ca
    H[:, 2:4, 2:4] += ca + cb
    H[:, :2, 2:4] -= ca
    H[:, 2:4, :2] -= ca
    H[:, 4:, 4:] += cb
    H[:, 2:4, 4:] -= cb
    H[:, 4:, 2:4] -= cb
    return c * F, c[:, None] * g, c[:, None, None] * H
