"""Natural meridional curvature of the embroidered region, as a correction of ``bending``.

The meridional bending term (Eq. 4, ``bending``) is w rho^2 / D tan^2(theta / 2) per hinge; with
a natural turning angle theta_0 it becomes w rho^2 / D (T - T_0)^2, T = tan(theta/2),
T_0 = tan(theta_0/2). This term is the difference,

    E_nc = (1/N) sum_i w_b^(i) bending_scale g_i rho_i^2 / D_i (T_0i^2 - 2 T_0i T_i),

over the hinges of the patch (g_i = 1 for hinges strictly inside, 1/2 on the boundary node, 0
outside). The natural curvature is kappa p^2 (1/mm, weighted by p^2 like every embroidered
property of the model), turned into a hinge angle over the rest segment length:
theta_0 = -kappa p^2 lambda dR. kappa > 0 curls the patch towards the pop-up dome (the dome
has X = a x b < 0). The energy is +inf where bending's is (Y <= 0 or D <= 0 on a hinge of the
patch).

Derivatives: F = rho^2 / D G(X, Y), G = T_0^2 - 2 T_0 X / Y, through q = (rho, D, X, Y) with
the hinge chain rule of ``hinge``.
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit

from stitchswitch.reduced.model.terms.hinge import HESS_DOT, HESS_X, hinge_geometry, hinge_gradient, hinge_hessian
from stitchswitch.reduced.model.terms.protocol import Term
from stitchswitch.reduced.model.terms.segment import NO_HESSIAN, add_local


def hinge_coefficients(grid, kappa_per_mm: float, fill: float):
    """(weight w_b bending_scale g / N, T_0) per hinge."""
    n_h = grid.n_nodes - 2
    node = np.arange(n_h) + 1
    g = np.where(node < grid.n_inside, 1.0, np.where(node == grid.n_inside, 0.5, 0.0))
    theta0 = -kappa_per_mm * fill ** 2 * grid.lam[:n_h] * grid.dr_mm
    w = grid.w_b * grid.bending_scale * g / grid.n_nodes
    return np.ascontiguousarray(w), np.ascontiguousarray(np.tan(0.5 * theta0))


@njit(cache=True)
def _kernel(r, z, w, t0, grad, hb, want_g, want_h, hess_x, hess_dot):
    V = np.zeros((8, 6))    # gradients of rho, D, X, Y, rbar_i, rbar_i+1, |a|, |b|
    C = np.zeros((8, 8))
    W = np.empty((8, 6))
    g = np.empty(6)
    H = np.empty((6, 6))
    E = 0.0
    for i in range(r.size - 2):
        c = w[i]
        if c == 0.0:
            continue
        ar, az, br, bz, la, lb, m0, m1, X, Y, D = hinge_geometry(r, z, i)
        rho = r[i + 1]
        if Y <= 0.0 or D <= 0.0:
            return math.inf
        T0 = t0[i]
        iD, iY = 1.0 / D, 1.0 / Y
        G = T0 * T0 - 2.0 * T0 * X * iY
        GX, GY = -2.0 * T0 * iY, 2.0 * T0 * X * iY * iY
        GXY, GYY = 2.0 * T0 * iY * iY, -4.0 * T0 * X * iY * iY * iY
        A = rho * rho * iD                      # rho^2 / D
        F = A * G
        E += c * F
        if not want_g:
            continue
        Fr, FD, FX, FY = 2.0 * rho * G * iD, -F * iD, A * GX, A * GY
        uar, uaz, ubr, ubz = hinge_gradient(g, V, c, Fr, FD, FX, FY, ar, az, br, bz, la, lb,
                                            m0, m1)
        if want_h:
            C[0, 0] = 2.0 * G * iD
            C[0, 1] = C[1, 0] = -2.0 * rho * G * iD * iD
            C[0, 2] = C[2, 0] = 2.0 * rho * GX * iD
            C[0, 3] = C[3, 0] = 2.0 * rho * GY * iD
            C[1, 1] = 2.0 * F * iD * iD
            C[1, 2] = C[2, 1] = -FX * iD
            C[1, 3] = C[3, 1] = -FY * iD
            C[2, 2] = 0.0
            C[2, 3] = C[3, 2] = A * GXY
            C[3, 3] = A * GYY
            hinge_hessian(H, C, V, W, c, FX, FY, FD, hess_x, hess_dot, m0, m1, la, lb,
                          uar, uaz, ubr, ubz)
        add_local(grad, hb, 2 * i, g, H, 6, want_h)
    return E


def energy(r, z, coef) -> float:
    return _kernel(r, z, coef[0], coef[1], np.empty(0), NO_HESSIAN, False, False, HESS_X, HESS_DOT)


def accumulate(r, z, coef, grad, hb) -> float:
    """Add the gradient (and the Hessian if ``hb`` has columns) into grad / hb; return E."""
    return _kernel(r, z, coef[0], coef[1], grad, hb, True, hb.shape[1] > 0, HESS_X, HESS_DOT)


def term(kappa_per_mm: float, fill: float) -> Term:
    """The natural-curvature term of a patch of fill ``fill`` with curvature kappa p^2."""
    def coefficients(grid):
        return hinge_coefficients(grid, kappa_per_mm, fill)

    return Term("natural_curvature", stencil=3, offset=0, coefficients=coefficients,
                energy=energy, accumulate=accumulate)
