"""Discrete-shell bending term (Eq. 4), the axisymmetric reduction of the hinge energy of
Jourdan et al. / Grinspun et al. (tan(theta/2) form).

Hinge i sits at node i+1 between segment vectors a = p_{i+1} - p_i and b = p_{i+2} - p_{i+1}:

    E_b = (1/N) sum_i w_b^(i) rho^2 / D * tan^2(theta/2),
    rho = r_{i+1},  D = rbar_i |a| + rbar_{i+1} |b|,  rbar_i = (r_i + r_{i+1}) / 2,
    tan(theta/2) = X / Y,  X = a x b = a_r b_z - a_z b_r,  Y = |a||b| + a.b.

rho^2 / D is (hinge circle length)^2 / (area of the two conical faces) up to 2 pi. Only the
meridional curvature is kept: the hoop curvature sin(phi)/r and Poisson coupling are dropped,
as in the paper. The energy is +inf for a full fold (Y <= 0) and for D <= 0.

Derivatives: F = X^2 G with G = rho^2 / (D Y^2) a monomial in positive quantities, so with
s = grad log G = 2 grad rho / rho - grad D / D - 2 grad Y / Y and v = grad X + X s,

    grad F      = F_X grad X + F_Y grad Y + F_D grad D + F_rho grad rho,
    Hess F      = 2 G v v^T - F s s^T + F (grad D grad D^T / D^2 + 2 grad Y grad Y^T / Y^2
                  - 2 grad rho grad rho^T / rho^2) + F_X Hess X + F_Y Hess Y + F_D Hess D:

four rank-one products instead of the general chain rule V^T C V through (rho, D, X, Y) that
the other hinge energies share (``hinge``). Hess X and Hess(a.b) are constant; Hess Y and
Hess D add the segment-length Hessians and sparse cross products. With every term written out
as scalars the Hessian costs a third of the chain rule's (the bending Hessian was the largest
part of a Newton iteration). tests/test_energy_terms.py checks gradient and Hessian by finite
differences.
"""
from __future__ import annotations

import math

from numba import njit

from stitchswitch.reduced.model.terms.hinge import hinge_shape
from stitchswitch.reduced.model.terms.protocol import Term
from stitchswitch.reduced.model.terms.segment import segment_lengths


def coefficients(grid):
    """(bending weight per hinge,): w_b bending_scale / N; see ``discretization`` for why
    bending is scaled with (dR_max/dR)^2."""
    return (grid.w_b * grid.bending_scale / grid.n_nodes,)


@njit(cache=True)
def _energy(r, z, w):
    return energy_lengths(r, z, w, segment_lengths(r, z))


@njit(cache=True)
def energy_lengths(r, z, w, lengths):
    """The energy with the segment lengths given (``segment.segment_lengths``: a caller that
    has them already saves two square roots per hinge)."""
    E = 0.0
    for i in range(r.size - 2):
        X, Y, D = hinge_shape(r, z, i, lengths[i], lengths[i + 1])[8:]
        if Y <= 0.0 or D <= 0.0:
            return math.inf
        E += w[i] * r[i + 1] * r[i + 1] * X * X / (D * Y * Y)
    return E


@njit(cache=True)
def _kernel(r, z, w, grad, hb, want_h):
    return kernel_lengths(r, z, w, segment_lengths(r, z), grad, hb, want_h)


@njit(cache=True)
def kernel_lengths(r, z, w, lengths, grad, hb, want_h):
    """Energy, gradient and (``want_h``) banded Hessian with the segment lengths given, written
    out with scalars: the local vectors are six named values each and every Hessian entry is
    added straight into the band (the constant Hessians of X and a.b, ``hinge.HESS_X`` and
    ``HESS_DOT``, are written out too). Local arrays would cost twice as much: the compiler
    cannot keep them in registers next to the stores into ``hb``."""
    E = 0.0
    for i in range(r.size - 2):
        ar, az, br, bz, la, lb, m0, m1, X, Y, D = hinge_shape(r, z, i, lengths[i], lengths[i + 1])
        rho = r[i + 1]
        iD, iY, ir = 1.0 / D, 1.0 / Y, 1.0 / rho
        G = rho * rho * iD * iY * iY
        F = G * X * X
        c = w[i]
        E += c * F
        uar, uaz, ubr, ubz = ar / la, az / la, br / lb, bz / lb
        # gradients of X, Y = |a||b| + a.b and D = rbar_i |a| + rbar_i+1 |b| over the local
        # dofs (r_i, z_i, r_i+1, z_i+1, r_i+2, z_i+2); grad|a| = (-ua, ua, 0), grad|b| = (0, -ub, ub)
        gX0, gX1, gX2, gX3, gX4, gX5 = -bz, br, bz + az, -br - ar, -az, ar
        gY0, gY1 = -lb * uar - br, -lb * uaz - bz
        gY2, gY3 = lb * uar - la * ubr + br - ar, lb * uaz - la * ubz + bz - az
        gY4, gY5 = la * ubr + ar, la * ubz + az
        gD0, gD1 = -m0 * uar + 0.5 * la, -m0 * uaz
        gD2, gD3 = m0 * uar - m1 * ubr + 0.5 * (la + lb), m0 * uaz - m1 * ubz
        gD4, gD5 = m1 * ubr + 0.5 * lb, m1 * ubz
        FX, FY, FD = 2.0 * G * X, -2.0 * F * iY, -F * iD
        a = 2 * i
        grad[a] += c * (FD * gD0 + FX * gX0 + FY * gY0)
        grad[a + 1] += c * (FD * gD1 + FX * gX1 + FY * gY1)
        grad[a + 2] += c * (FD * gD2 + FX * gX2 + FY * gY2) + c * 2.0 * F * ir
        grad[a + 3] += c * (FD * gD3 + FX * gX3 + FY * gY3)
        grad[a + 4] += c * (FD * gD4 + FX * gX4 + FY * gY4)
        grad[a + 5] += c * (FD * gD5 + FX * gX5 + FY * gY5)
        if want_h:
            # s = grad log G, v = grad X + X s
            s0, s1 = -gD0 * iD - 2.0 * gY0 * iY, -gD1 * iD - 2.0 * gY1 * iY
            s2, s3 = -gD2 * iD - 2.0 * gY2 * iY + 2.0 * ir, -gD3 * iD - 2.0 * gY3 * iY
            s4, s5 = -gD4 * iD - 2.0 * gY4 * iY, -gD5 * iD - 2.0 * gY5 * iY
            v0, v1, v2 = gX0 + X * s0, gX1 + X * s1, gX2 + X * s2
            v3, v4, v5 = gX3 + X * s3, gX4 + X * s4, gX5 + X * s5
            # the four rank-one products, scaled: c (2 G v v^T - F s s^T + F/D^2 gD gD^T
            # + 2 F/Y^2 gY gY^T)
            kv, ks, kd, ky = 2.0 * c * G, -c * F, c * F * iD * iD, 2.0 * c * F * iY * iY
            pv0, pv1, pv2, pv3, pv4, pv5 = kv * v0, kv * v1, kv * v2, kv * v3, kv * v4, kv * v5
            ps0, ps1, ps2, ps3, ps4, ps5 = ks * s0, ks * s1, ks * s2, ks * s3, ks * s4, ks * s5
            pd0, pd1, pd2, pd3, pd4, pd5 = kd * gD0, kd * gD1, kd * gD2, kd * gD3, kd * gD4, kd * gD5
            py0, py1, py2, py3, py4, py5 = ky * gY0, ky * gY1, ky * gY2, ky * gY3, ky * gY4, ky * gY5
            # F_X Hess X + F_Y Hess(a.b) (constant matrices), F_Y (grad|a| grad|b|^T + T),
            # F_D (grad rbar grad|.|^T + T) with grad rbar_i = (e_0 + e_2) / 2 and
            # grad rbar_i+1 = (e_2 + e_4) / 2, -2 F / rho^2 at (r_i+1, r_i+1), and the two
            # segment-length Hessians k (I - u u^T) / l with k = F_D rbar + F_Y |other|
            fx, fy, cd, crho = c * FX, c * FY, 0.5 * c * FD, 2.0 * c * F * ir * ir
            qrr, qrz, qzr, qzz = fy * uar * ubr, fy * uar * ubz, fy * uaz * ubr, fy * uaz * ubz
            ka, kb = c * (FD * m0 + FY * lb) / la, c * (FD * m1 + FY * la) / lb
            parr, parz, pazz = ka * (1.0 - uar * uar), -ka * uar * uaz, ka * (1.0 - uaz * uaz)
            pbrr, pbrz, pbzz = kb * (1.0 - ubr * ubr), -kb * ubr * ubz, kb * (1.0 - ubz * ubz)
            hb[0, a + 0] += pv0 * v0 + ps0 * s0 + pd0 * gD0 + py0 * gY0 - 2.0 * cd * uar + parr
            hb[1, a + 0] += pv1 * v0 + ps1 * s0 + pd1 * gD0 + py1 * gY0 - cd * uaz + parz
            hb[0, a + 1] += pv1 * v1 + ps1 * s1 + pd1 * gD1 + py1 * gY1 + pazz
            hb[2, a + 0] += pv2 * v0 + ps2 * s0 + pd2 * gD0 + py2 * gY0 + fy + qrr - parr
            hb[1, a + 1] += (pv2 * v1 + ps2 * s1 + pd2 * gD1 + py2 * gY1 - fx + qzr - cd * uaz
                             - parz)
            hb[0, a + 2] += (pv2 * v2 + ps2 * s2 + pd2 * gD2 + py2 * gY2 - 2.0 * fy - 2.0 * qrr
                             + 2.0 * cd * (uar - ubr) - crho + parr + pbrr)
            hb[3, a + 0] += (pv3 * v0 + ps3 * s0 + pd3 * gD0 + py3 * gY0 + fx + qrz + cd * uaz
                             - parz)
            hb[2, a + 1] += pv3 * v1 + ps3 * s1 + pd3 * gD1 + py3 * gY1 + fy + qzz - pazz
            hb[1, a + 2] += (pv3 * v2 + ps3 * s2 + pd3 * gD2 + py3 * gY2 - qzr - qrz + cd * (uaz
                             - ubz) + parz + pbrz)
            hb[0, a + 3] += (pv3 * v3 + ps3 * s3 + pd3 * gD3 + py3 * gY3 - 2.0 * fy - 2.0 * qzz
                             + pazz + pbzz)
            hb[4, a + 0] += pv4 * v0 + ps4 * s0 + pd4 * gD0 + py4 * gY0 - fy - qrr
            hb[3, a + 1] += pv4 * v1 + ps4 * s1 + pd4 * gD1 + py4 * gY1 + fx - qzr
            hb[2, a + 2] += pv4 * v2 + ps4 * s2 + pd4 * gD2 + py4 * gY2 + fy + qrr - pbrr
            hb[1, a + 3] += (pv4 * v3 + ps4 * s3 + pd4 * gD3 + py4 * gY3 - fx + qzr - cd * ubz
                             - pbrz)
            hb[0, a + 4] += pv4 * v4 + ps4 * s4 + pd4 * gD4 + py4 * gY4 + 2.0 * cd * ubr + pbrr
            hb[5, a + 0] += pv5 * v0 + ps5 * s0 + pd5 * gD0 + py5 * gY0 - fx - qrz
            hb[4, a + 1] += pv5 * v1 + ps5 * s1 + pd5 * gD1 + py5 * gY1 - fy - qzz
            hb[3, a + 2] += (pv5 * v2 + ps5 * s2 + pd5 * gD2 + py5 * gY2 + fx + qrz + cd * ubz
                             - pbrz)
            hb[2, a + 3] += pv5 * v3 + ps5 * s3 + pd5 * gD3 + py5 * gY3 + fy + qzz - pbzz
            hb[1, a + 4] += pv5 * v4 + ps5 * s4 + pd5 * gD4 + py5 * gY4 + cd * ubz + pbrz
            hb[0, a + 5] += pv5 * v5 + ps5 * s5 + pd5 * gD5 + py5 * gY5 + pbzz
    return E


def energy(r, z, coef) -> float:
    return _energy(r, z, coef[0])


def accumulate(r, z, coef, grad, hb) -> float:
    """Add the gradient (and the Hessian if ``hb`` has columns) into grad / hb; return E."""
    return _kernel(r, z, coef[0], grad, hb, hb.shape[1] > 0)


TERM = Term("bending", stencil=3, offset=0, coefficients=coefficients, energy=energy,
            accumulate=accumulate)
