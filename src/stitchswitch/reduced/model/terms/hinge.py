"""Kernels shared by the hinge energies (``bending``, ``natural_curvature``).

Hinge i sits at node i+1 between segment vectors a = p_{i+1} - p_i and b = p_{i+2} - p_{i+1}.
A hinge energy is a function F(rho, D, X, Y) of

    rho = r_{i+1},  D = rbar_i |a| + rbar_{i+1} |b|,  rbar_i = (r_i + r_{i+1}) / 2,
    X = a x b = a_r b_z - a_z b_r,  Y = |a||b| + a.b      (tan(theta/2) = X / Y).

Its derivatives follow by the chain rule through q = (rho, D, X, Y), each with a simple
gradient in the six local dofs (r_i, z_i, r_{i+1}, z_{i+1}, r_{i+2}, z_{i+2}). The Hessian is
sum_kl F_kl (grad q_k)(grad q_l)^T + sum_k F_k Hess q_k, where Hess X and Hess(a.b) are
constant, Hess |a| = [[P, -P], [-P, P]] with P = (I - u u^T)/|a|, and the products inside
Hess D and Hess Y are gathered with the first sum as V^T C V.
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit

from stitchswitch.reduced.model.terms.segment import add_length_hessian

_EA = np.array([[-1, 0, 1, 0, 0, 0], [0, -1, 0, 1, 0, 0]], dtype=float)   # a = EA q
_EB = np.array([[0, 0, -1, 0, 1, 0], [0, 0, 0, -1, 0, 1]], dtype=float)   # b = EB q
_M = np.array([[0.0, 1.0], [-1.0, 0.0]])
HESS_X = _EA.T @ _M @ _EB + _EB.T @ _M.T @ _EA      # X = a^T M b is bilinear
HESS_DOT = _EA.T @ _EB + _EB.T @ _EA                 # a.b is bilinear


@njit(cache=True)
def hinge_geometry(r, z, i):
    """The segment vectors a, b, their lengths, rbar_i, rbar_{i+1} and X, Y, D of hinge i."""
    ar, az = r[i + 1] - r[i], z[i + 1] - z[i]
    br, bz = r[i + 2] - r[i + 1], z[i + 2] - z[i + 1]
    return hinge_shape(r, z, i, math.sqrt(ar * ar + az * az), math.sqrt(br * br + bz * bz))


@njit(cache=True)
def hinge_shape(r, z, i, la, lb):
    """``hinge_geometry`` with the two segment lengths given (``segment.segment``'s lengths are
    the same numbers): for a caller that has them already."""
    ar, az = r[i + 1] - r[i], z[i + 1] - z[i]
    br, bz = r[i + 2] - r[i + 1], z[i + 2] - z[i + 1]
    m0, m1 = 0.5 * (r[i] + r[i + 1]), 0.5 * (r[i + 1] + r[i + 2])
    X = ar * bz - az * br
    Y = la * lb + ar * br + az * bz
    D = m0 * la + m1 * lb
    return ar, az, br, bz, la, lb, m0, m1, X, Y, D


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
    # W = C V with the known zeros of C skipped (C is zero outside its 4 x 4 block and the
    # three cross terms above); the sums keep the order of the full product, so the result
    # is the same to the last bit
    for s in range(6):
        for k in range(4):
            W[k, s] = C[k, 0] * V[0, s] + C[k, 1] * V[1, s] + C[k, 2] * V[2, s] + C[k, 3] * V[3, s]
        W[4, s] = FD * V[6, s]
        W[5, s] = FD * V[7, s]
        W[6, s] = FD * V[4, s] + FY * V[7, s]
        W[7, s] = FD * V[5, s] + FY * V[6, s]
    for p in range(6):
        for s in range(p + 1):
            acc = FX * hess_x[p, s] + FY * hess_dot[p, s]
            for k in range(8):
                acc += V[k, p] * W[k, s]
            H[p, s] = c * acc
    add_length_hessian(H, 0, c * ca, uar, uaz, la)
    add_length_hessian(H, 2, c * cb, ubr, ubz, lb)
