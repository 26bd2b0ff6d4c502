"""Discrete-shell bending term (Eq. 4), the axisymmetric reduction of the hinge energy of
Jourdan et al. / Grinspun et al. (tan(theta/2) form).

Hinge i sits at node i+1 between segment vectors a = p_{i+1} - p_i and b = p_{i+2} - p_{i+1}:

    E_b = (1/N) sum_i w_b^(i) rho^2 / D * tan^2(theta/2),
    rho = r_{i+1},  D = rbar_i |a| + rbar_{i+1} |b|,  rbar_i = (r_i + r_{i+1}) / 2,
    tan(theta/2) = X / Y,  X = a x b = a_r b_z - a_z b_r,  Y = |a||b| + a.b.

rho^2 / D is (hinge circle length)^2 / (area of the two conical faces) up to 2 pi. Only the
meridional curvature is kept: the hoop curvature sin(phi)/r and Poisson coupling are dropped,
as in the paper. The energy is +inf for a full fold (Y <= 0) and for D <= 0.

Derivatives: F(q) = rho^2 X^2 / (D Y^2) has closed-form partials in q = (rho, D, X, Y); the
chain rule through q is shared with the other hinge energies (``hinge``).
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit

from stitchswitch.reduced.model.terms.hinge import HESS_DOT, HESS_X, hinge_geometry, hinge_gradient, hinge_hessian
from stitchswitch.reduced.model.terms.protocol import Term
from stitchswitch.reduced.model.terms.segment import add_local


def coefficients(grid):
    """(bending weight per hinge, the constant Hessians of X and a.b). The weight is
    w_b bending_scale / N: see ``discretization`` for why bending is scaled with (dR_max/dR)^2."""
    return grid.w_b * grid.bending_scale / grid.n_nodes, HESS_X, HESS_DOT


@njit(cache=True)
def _energy(r, z, w):
    E = 0.0
    for i in range(r.size - 2):
        X, Y, D = hinge_geometry(r, z, i)[8:]
        if Y <= 0.0 or D <= 0.0:
            return math.inf
        E += w[i] * r[i + 1] * r[i + 1] * X * X / (D * Y * Y)
    return E


@njit(cache=True)
def _kernel(r, z, w, grad, hb, want_h, hess_x, hess_dot):
    V = np.zeros((8, 6))    # gradients of rho, D, X, Y, rbar_i, rbar_i+1, |a|, |b|
    C = np.zeros((8, 8))    # matching second-order coefficients
    W = np.empty((8, 6))
    g = np.empty(6)
    H = np.empty((6, 6))
    E = 0.0
    for i in range(r.size - 2):
        ar, az, br, bz, la, lb, m0, m1, X, Y, D = hinge_geometry(r, z, i)
        rho = r[i + 1]
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


TERM = Term("bending", stencil=3, offset=0, coefficients=coefficients, energy=energy,
            accumulate=accumulate)
