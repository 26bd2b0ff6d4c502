"""Energy density of the axisymmetric shell reference, with its first and second derivatives.

The continuum limit of the reduced model's energy (``docs/model.md``), per unit rest radius S,
everything in mm (the reduced energy in dR units is this integral divided by N dR^2):

    f = k_r lam S max(l - lam, 0)^2                 tension-only meridional membrane
      + c k_r lam^3 S psi(l / lam) + c_jam k_r lam S max(j lam - l, 0)^2
                                                    compressive response (as the reduced model)
      + k_theta (r - lam S)^2 / (lam S)             circumferential membrane
      + w_log h(r - lam S; gamma)                   hardening (sign-corrected Eq. 5)
      + B r l (kappa_s^2 + H (kappa_t^2 + 2 nu kappa_s kappa_t))      bending

with l = |(r', z')| the meridional stretch, kappa_s = (r' z'' - z' r'') / l^3 the meridional
curvature, kappa_t = -z' / (l r) the hoop (parallel) curvature sin(phi) / r, and
B = w_b dR_ref^2 / 8: the limit of the discrete hinge energy, w_b r kappa^2 l / 8 per node,
with the bending weights defined at dR_ref = ``discretization.BENDING_REFERENCE_MM`` (0.5 mm).
H = 1 switches on hoop bending and nu the Poisson coupling: the physics the reduced model drops.
With H = 0 the density is exactly the reduced model's continuum limit.

The derivatives are taken with respect to q = (r, r', z', r'', z'') at every quadrature point
(z itself does not enter: a rigid z shift costs nothing), through the scalars l, X = r' z'' -
z' r'' and the bending monomials c r^a X^b l^e z'^g, whose partial derivatives are exact.
"""
from __future__ import annotations

import numpy as np

from stitchswitch.reduced.model.discretization import BENDING_REFERENCE_MM
from stitchswitch.reduced.model.terms.hardening import h as hardening_h

NQ = 5   # r, r', z', r'', z''


def _psi(s):
    """psi(s) = 2 (s - 1 - ln s) for s < 1 (0 otherwise) and its first two derivatives; +inf
    where s <= 0."""
    slack = s < 1.0
    ss = np.where(s > 0.0, np.minimum(s, 1.0), np.nan)
    with np.errstate(invalid="ignore", divide="ignore"):
        v = np.where(s > 0.0, np.where(slack, 2.0 * (ss - 1.0 - np.log(ss)), 0.0), np.inf)
        return (v, np.where(slack, 2.0 * (1.0 - 1.0 / ss), 0.0), np.where(slack, 2.0 / (ss * ss), 0.0))


def _bending_monomials(hoop: float, nu: float):
    """(coefficient, exponents of r, X, l, z') of the bending density / B."""
    terms = [(1.0, (1, 2, -5, 0))]
    if hoop:
        terms += [(hoop, (-1, 0, -1, 2)), (-2.0 * nu * hoop, (0, 1, -3, 1))]
    return terms


def _monomial_derivatives(terms, v):
    """Value, gradient (4, ...) and Hessian (4, 4, ...) of sum_c c prod v_i^a_i."""
    val = np.zeros_like(v[0])
    grad = np.zeros((4,) + v[0].shape)
    hess = np.zeros((4, 4) + v[0].shape)

    def mono(c, exps):
        out = c * np.ones_like(v[0])
        for vi, a in zip(v, exps):
            if a:
                out = out * vi ** a
        return out

    for c, a in terms:
        val += mono(c, a)
        for i in range(4):
            if not a[i]:
                continue
            ai = list(a)
            ai[i] -= 1
            grad[i] += mono(c * a[i], ai)
            for j in range(4):
                if not ai[j]:
                    continue
                aij = list(ai)
                aij[j] -= 1
                hess[i, j] += mono(c * a[i] * ai[j], aij)
    return val, grad, hess


def density(q, S, coef, hessian: bool = True):
    """f, df/dq (5, ...) and d2f/dq2 (5, 5, ...) at quadrature points.

    ``q``: (5, ...) values of r, r', z', r'', z''; ``S``: rest radius (mm); ``coef``: dict of
    arrays/scalars lam, k_r, k_theta, w_b, w_log, gamma, c, jam, c_jam, hoop, nu (see module
    docstring)."""
    r, rp, zp, rpp, zpp = q
    lam, k_r = coef["lam"], coef["k_r"]
    l = np.sqrt(rp * rp + zp * zp)
    u_r, u_z = rp / l, zp / l

    # membrane along the meridian: a function of l only
    a = k_r * lam * S
    s = np.maximum(l - lam, 0.0)
    cw = coef["c"] * k_r * lam ** 3 * S
    psi, dpsi, d2psi = _psi(l / lam)
    aj = coef["c_jam"] * a
    g = np.maximum(coef["jam"] * lam - l, 0.0)
    m = a * s * s + cw * psi + aj * g * g
    m1 = 2 * a * s + cw * dpsi / lam - 2 * aj * g
    m2 = 2 * a * (s > 0) + cw * d2psi / lam ** 2 + 2 * aj * (g > 0)

    # hoop membrane and hardening: functions of r only
    eps = r - lam * S
    ring = lam * S
    hv, h1, h2 = hardening_h(eps, coef["gamma"])
    n0 = coef["k_theta"] * eps * eps / ring + coef["w_log"] * hv
    n1 = 2 * coef["k_theta"] * eps / ring + coef["w_log"] * h1
    n2 = 2 * coef["k_theta"] / ring + coef["w_log"] * h2

    # bending: B * monomials in (r, X, l, z')
    B = coef["w_b"] * BENDING_REFERENCE_MM ** 2 / 8.0
    X = rp * zpp - zp * rpp
    bv, bg, bh = _monomial_derivatives(_bending_monomials(coef["hoop"], coef["nu"]), (r, X, l, zp))

    f = m + n0 + B * bv
    # gradients of the intermediates r, X, l, z' with respect to q
    zero = np.zeros_like(r)
    one = np.ones_like(r)
    J = np.array([[one, zero, zero, zero, zero],              # r
                  [zero, zpp, -rpp, -zp, rp],                 # X
                  [zero, u_r, u_z, zero, zero],               # l
                  [zero, zero, one, zero, zero]])             # z'
    grad = np.einsum("i...,iq...->q...", B * bg, J)
    grad[0] += n1
    grad[1] += m1 * u_r
    grad[2] += m1 * u_z
    if not hessian:
        return f, grad, None
    H = np.einsum("ip...,ij...,jq...->pq...", J, B * bh, J)
    H[0, 0] += n2
    # membrane through l, plus l's own curvature (membrane and bending)
    lcoef = m1 + B * bg[2]
    H[1, 1] += m2 * u_r * u_r + lcoef * (1 - u_r * u_r) / l
    H[1, 2] += m2 * u_r * u_z - lcoef * u_r * u_z / l
    H[2, 1] += m2 * u_r * u_z - lcoef * u_r * u_z / l
    H[2, 2] += m2 * u_z * u_z + lcoef * (1 - u_z * u_z) / l
    # X is bilinear: d2X/dr'dz'' = 1, d2X/dz'dr'' = -1
    bx = B * bg[1]
    H[1, 4] += bx
    H[4, 1] += bx
    H[2, 3] -= bx
    H[3, 2] -= bx
    return f, grad, H
