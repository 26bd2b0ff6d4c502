"""``tension_asymmetry``: a natural meridional curvature of the embroidered region.

Unequal top and bobbin thread tension makes a stitched layer curl. The meridional bending term
(Eq. 4, ``reduced.model.terms.bending``) is w rho^2 / D tan^2(theta / 2) per hinge; with a natural
turning angle theta_0 it becomes w rho^2 / D (T - T_0)^2, T = tan(theta/2), T_0 = tan(theta_0/2).
The effect adds the difference,

    E_ta = (1/N) sum_i w_b^(i) bending_scale g_i rho_i^2 / D_i (T_0i^2 - 2 T_0i T_i),

over the hinges of the patch (g_i = 1 for hinges strictly inside, 1/2 on the boundary node, 0
outside). The natural curvature is kappa p^2 (1/mm, weighted by p^2 like every embroidered
property of the model), turned into a hinge angle over the rest segment length:
theta_0 = -kappa p^2 lambda dR. kappa > 0 curls the patch towards the pop-up dome (the dome
has X = a x b < 0); kappa = 0 is the starting model.

Derivatives: F = rho^2 / D G(X, Y), G = T_0^2 - 2 T_0 X / Y, through q = (rho, D, X, Y) exactly
as in ``reduced.model.terms.bending`` (the same gradients of q, Hess X and a.b constant, Hess |a|
gathered with the products inside Hess D and Hess Y).
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit

from stitchswitch.reduced.model.terms.bending import HESS_DOT, HESS_X, hinge_gradient, hinge_hessian
from stitchswitch.reduced.model.terms.segment import NO_HESSIAN, add_local
from stitchswitch.validation.discovery.effects.registry import Effect, EffectParameter, register_effect

STENCIL = 3
OFFSET = 0


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
        ar, az = r[i + 1] - r[i], z[i + 1] - z[i]
        br, bz = r[i + 2] - r[i + 1], z[i + 2] - z[i + 1]
        la, lb = math.sqrt(ar * ar + az * az), math.sqrt(br * br + bz * bz)
        m0, m1, rho = 0.5 * (r[i] + r[i + 1]), 0.5 * (r[i + 1] + r[i + 2]), r[i + 1]
        X = ar * bz - az * br
        Y = la * lb + ar * br + az * bz
        D = m0 * la + m1 * lb
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


class _Term:
    __name__ = "effect_tension_asymmetry"
    STENCIL = STENCIL
    OFFSET = OFFSET

    def __init__(self, kappa_per_mm: float, fill: float):
        self.kappa_per_mm, self.fill = kappa_per_mm, fill

    def coefficients(self, grid):
        return hinge_coefficients(grid, self.kappa_per_mm, self.fill)

    @staticmethod
    def energy(r, z, coef) -> float:
        return _kernel(r, z, coef[0], coef[1], np.empty(0), NO_HESSIAN, False, False,
                       HESS_X, HESS_DOT)

    @staticmethod
    def accumulate(r, z, coef, grad, hb) -> float:
        return _kernel(r, z, coef[0], coef[1], grad, hb, True, hb.shape[1] > 0, HESS_X, HESS_DOT)


def term(kappa_per_mm: float, fill: float):
    """The natural-curvature term of a patch of fill ``fill``."""
    return _Term(kappa_per_mm, fill)


EFFECT = register_effect(Effect(
    name="tension_asymmetry",
    summary="natural meridional curvature kappa p^2 of the embroidered region (thread tension)",
    physics="Unequal top/bobbin thread tension makes the stitched layer curl: the bending term "
            "inside the patch gets a natural curvature kappa p^2 (1/mm), w (T - T_0)^2 instead "
            "of w T^2 per hinge. kappa > 0 curls towards the dome; kappa = 0 is the starting "
            "model.",
    parameters=(EffectParameter("kappa_per_mm", "1/mm", -0.2, 0.2, probe=0.01,
                                hidden=(-0.06, -0.04), signed=True),),
    terms=lambda patch, material, v: (term(v[0], patch.fill),),
))
