"""Discrete-shell bending term (Eq. 4), the axisymmetric reduction of the hinge energy of
Jourdan et al. / Grinspun et al. (tan(theta/2) form).

Hinge i sits at node i+1 between segment vectors a = p_{i+1} - p_i and b = p_{i+2} - p_{i+1}:

    E_b = (1/N) sum_i w_b^(i) rho^2 / D * tan^2(theta/2),
    rho = r_{i+1},  D = rbar_i |a| + rbar_{i+1} |b|,  rbar_i = (r_i + r_{i+1}) / 2,
    tan(theta/2) = X / Y,  X = a x b = a_r b_z - a_z b_r,  Y = |a||b| + a.b.

rho^2 / D is (hinge circle length)^2 / (area of the two conical faces) up to 2 pi. Only the
meridional curvature is kept: the hoop curvature sin(phi)/r and Poisson coupling are dropped,
as in the paper. The energy is +inf for a full fold (Y <= 0) and for D <= 0.

Derivatives: chain rule through q = (rho, D, X, Y), each with a simple gradient in the six
local dofs (r_i, z_i, r_{i+1}, z_{i+1}, r_{i+2}, z_{i+2}); F(q) = rho^2 X^2 / (D Y^2) has
closed-form partials. The Hessian is sum_kl F_kl (grad q_k)(grad q_l)^T + sum_k F_k Hess q_k,
where Hess X and Hess(a.b) are constant, Hess |a| = [[P, -P], [-P, P]] with P = (I - u u^T)/|a|,
and the products inside Hess D and Hess Y are gathered with the first sum as V^T C V.
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit

from stitchswitch.reduced.model.terms.segment import add_local

STENCIL = 3
OFFSET = 0

_EA = np.array([[-1, 0, 1, 0, 0, 0], [0, -1, 0, 1, 0, 0]], dtype=float)   # a = EA q
_EB = np.array([[0, 0, -1, 0, 1, 0], [0, 0, 0, -1, 0, 1]], dtype=float)   # b = EB q
_M = np.array([[0.0, 1.0], [-1.0, 0.0]])
HESS_X = _EA.T @ _M @ _EB + _EB.T @ _M.T @ _EA      # X = a^T M b is bilinear
HESS_DOT = _EA.T @ _EB + _EB.T @ _EA                 # a.b is bilinear


def coefficients(grid):
    """(bending weight per hinge, the constant Hessians of X and a.b). The weight is
    w_b bending_scale / N: see ``discretization`` for why bending is scaled with (dR_max/dR)^2."""
    return grid.w_b * grid.bending_scale / grid.n_nodes, HESS_X, HESS_DOT


@njit(cache=True)
def _energy(r, z, w):
    E = 0.0
    for i in range(r.size - 2):
        ar, az = r[i + 1] - r[i], z[i + 1] - z[i]
        br, bz = r[i + 2] - r[i + 1], z[i + 2] - z[i + 1]
        la, lb = math.sqrt(ar * ar + az * az), math.sqrt(br * br + bz * bz)
        X = ar * bz - az * br
        Y = la * lb + ar * br + az * bz
        D = 0.5 * (r[i] + r[i + 1]) * la + 0.5 * (r[i + 1] + r[i + 2]) * lb
        if Y <= 0.0 or D <= 0.0:
            return math.inf
        E += w[i] * r[i + 1] * r[i + 1] * X * X / (D * Y * Y)
    return E


@njit(cache=True)
def _add_length_hessian(H, off, k, ur, uz, l):
    """H += k [[P, -P], [-P, P]] (lower triangle) at local dofs off..off+3, P = (I - u u^T) / l."""
    prr, prz, pzz = k * (1.0 - ur * ur) / l, -k * ur * uz / l, k * (1.0 - uz * uz) / l
    H[off, off] += prr
    H[off + 1, off] += prz
    H[off + 1, off + 1] += pzz
    H[off + 2, off] -= prr
    H[off + 2, off + 1] -= prz
    H[off + 3, off] -= prz
    H[off + 3, off + 1] -= pzz
    H[off + 2, off + 2] += prr
    H[off + 3, off + 2] += prz
    H[off + 3, off + 3] += pzz


@njit(cache=True)
def hinge_gradient(g, V, c, Fr, FD, FX, FY, ar, az, br, bz, la, lb, m0, m1):
    """The chain rule of a hinge's gradient, shared by every hinge energy F(rho, D, X, Y) with
    partial derivatives Fr, FD, FX, FY: writes g = c dF/dx over the six local dofs and the
    Jacobian V of the intermediate variables (rho, D, X, Y, rbar_i, rbar_i+1, |a|, |b|);
    returns the unit vectors of the two segments (for ``hinge_hessian``)."""
    uar, uaz, ubr, ubz = ar / la, az / la, br / lb, bz / lb
    dla = (-uar, -uaz, uar, uaz, 0.0, 0.0)
    dlb = (0.0, 0.0, -ubr, -ubz, ubr, ubz)
    dX = (-bz, br, bz + az, -br - ar, -az, ar)
    dS = (-br, -bz, br - ar, bz - az, ar, az)
    gm0 = (0.5, 0.0, 0.5, 0.0, 0.0, 0.0)
    gm1 = (0.0, 0.0, 0.5, 0.0, 0.5, 0.0)
    for p in range(6):
        dY = lb * dla[p] + la * dlb[p] + dS[p]
        dD = m0 * dla[p] + m1 * dlb[p] + la * gm0[p] + lb * gm1[p]
        g[p] = c * (FD * dD + FX * dX[p] + FY * dY)
        V[1, p], V[2, p], V[3, p] = dD, dX[p], dY
        V[4, p], V[5, p], V[6, p], V[7, p] = gm0[p], gm1[p], dla[p], dlb[p]
    g[2] += c * Fr
    V[0, 2] = 1.0
    return uar, uaz, ubr, ubz


@njit(cache=True)
def hinge_hessian(H, C, V, W, c, FX, FY, FD, hess_x, hess_dot, m0, m1, la, lb,
                  uar, uaz, ubr, ubz):
    """The chain rule of a hinge's Hessian, shared by every hinge energy: with C[:4, :4] the
    second derivatives in the hinge's intermediate variables and V their Jacobian, completes C
    (the cross terms of D and Y, weighted FD and FY), and writes the lower triangle of
    H = c (V^T C V + FX Hess x + FY Hess(a.b)) plus the Hessians of the two segment lengths."""
    C[4, 6] = C[6, 4] = FD       # Hess D contains grad(rbar_i) x grad|a| + transpose
    C[5, 7] = C[7, 5] = FD
    C[6, 7] = C[7, 6] = FY       # Hess Y contains grad|a| x grad|b| + transpose
    ca = FD * m0 + FY * lb       # coefficient of Hess |a|
    cb = FD * m1 + FY * la
    for k in range(8):
        for s in range(6):
            acc = 0.0
            for m in range(8):
                acc += C[k, m] * V[m, s]
            W[k, s] = acc
    for p in range(6):
        for s in range(p + 1):
            acc = FX * hess_x[p, s] + FY * hess_dot[p, s]
            for k in range(8):
                acc += V[k, p] * W[k, s]
            H[p, s] = c * acc
    _add_length_hessian(H, 0, c * ca, uar, uaz, la)
    _add_length_hessian(H, 2, c * cb, ubr, ubz, lb)


@njit(cache=True)
def _kernel(r, z, w, grad, hb, want_h, hess_x, hess_dot):
    V = np.zeros((8, 6))    # gradients of rho, D, X, Y, rbar_i, rbar_i+1, |a|, |b|
    C = np.zeros((8, 8))    # matching second-order coefficients
    W = np.empty((8, 6))
    g = np.empty(6)
    H = np.empty((6, 6))
    E = 0.0
    for i in range(r.size - 2):
        ar, az = r[i + 1] - r[i], z[i + 1] - z[i]
        br, bz = r[i + 2] - r[i + 1], z[i + 2] - z[i + 1]
        la, lb = math.sqrt(ar * ar + az * az), math.sqrt(br * br + bz * bz)
        m0, m1, rho = 0.5 * (r[i] + r[i + 1]), 0.5 * (r[i + 1] + r[i + 2]), r[i + 1]
        X = ar * bz - az * br
        Y = la * lb + ar * br + az * bz
        D = m0 * la + m1 * lb
        iD, iY = 1.0 / D, 1.0 / Y
        q = iD * iY * iY
        F = rho * rho * X * X * q
        Fr, FD, FX, FY = 2.0 * rho * X * X * q, -F * iD, 2.0 * rho * rho * X * q, -2.0 * F * iY
        c = w[i]
        E += c * F
        uar, uaz, ubr, ubz = hinge_gradient(g, V, c, Fr, FD, FX, FY, ar, az, br, bz, la, lb,
                                            m0, m1)
        if want_h:
            C[0, 0] = 2.0 * X * X * q
            C[0, 1] = C[1, 0] = -Fr * iD
            C[0, 2] = C[2, 0] = 4.0 * rho * X * q
            C[0, 3] = C[3, 0] = -2.0 * Fr * iY
            C[1, 1] = 2.0 * F * iD * iD
            C[1, 2] = C[2, 1] = -FX * iD
            C[1, 3] = C[3, 1] = 2.0 * F * iD * iY
            C[2, 2] = 2.0 * rho * rho * q
            C[2, 3] = C[3, 2] = -2.0 * FX * iY
            C[3, 3] = 6.0 * F * iY * iY
            hinge_hessian(H, C, V, W, c, FX, FY, FD, hess_x, hess_dot, m0, m1, la, lb,
                          uar, uaz, ubr, ubz)
        add_local(grad, hb, 2 * i, g, H, 6, want_h)
    return E


def energy(r, z, coef) -> float:
    return _energy(r, z, coef[0])


def accumulate(r, z, coef, grad, hb) -> float:
    """Add the gradient (and the Hessian if ``hb`` has columns) into grad / hb; return E."""
    w, hess_x, hess_dot = coef
    return _kernel(r, z, w, grad, hb, hb.shape[1] > 0, hess_x, hess_dot)
