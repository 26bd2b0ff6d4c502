"""Hoop bending: bending of the parallels (hoop curvature sin(phi)/r), which Eq. 4 drops.

The shell reference's density (``fem_reference.density``) has the bending term
B r l (kappa_s^2 + H kappa_t^2) with kappa_t = sin(phi) / r = -z' / (l r); the reduced model keeps
only kappa_s. Its hoop part is B z'^2 / (l r) per unit rest radius. Discretized per segment i
(dR units, dz = z_{i+1} - z_i, l the segment length, rbar = (r_i + r_{i+1}) / 2), with the
meridional term's own constant (its continuum limit is B = w_b bending_scale / 8 per 1/N):

    E_hoop = (H / N) sum_i (w_b^(i) bending_scale / 8) dz_i^2 / (l_i rbar_i),

H = 1 being an isotropic shell's hoop bending with the model's bending stiffness. Segment i uses
hinge i's weight (the last segment the fabric's). The energy is +inf for a zero-length segment
or rbar <= 0.

Derivatives through q = (dz, l, rbar): F = c dz^2 / (l m) has closed-form partials; the
Hessian is V^T C V + F_l Hess l (dz and rbar are linear in the dofs).
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit

from stitchswitch.reduced.model.terms.protocol import Term
from stitchswitch.reduced.model.terms.segment import NO_GRADIENT, NO_HESSIAN, add_length_hessian, add_local


def segment_weights(grid) -> np.ndarray:
    """w_b bending_scale / 8 per segment (hinge i's weight; the last segment repeats it)."""
    w = np.concatenate([grid.w_b, grid.w_b[-1:]])
    return w * grid.bending_scale / 8.0


@njit(cache=True)
def _kernel(r, z, c, grad, hb, want_g, want_h):
    g = np.empty(4)
    H = np.zeros((4, 4))
    V = np.zeros((3, 4))
    C = np.empty((3, 3))
    E = 0.0
    for i in range(r.size - 1):
        vr, dz = r[i + 1] - r[i], z[i + 1] - z[i]
        l = math.sqrt(vr * vr + dz * dz)
        m = 0.5 * (r[i] + r[i + 1])
        if l <= 0.0 or m <= 0.0:
            return math.inf
        ci = c[i]
        F = ci * dz * dz / (l * m)
        E += F
        if not want_g:
            continue
        ur, uz = vr / l, dz / l
        Fz, Fl, Fm = 2.0 * ci * dz / (l * m), -F / l, -F / m
        # gradients of dz, l, rbar over (r_i, z_i, r_i+1, z_i+1)
        V[0, 0], V[0, 1], V[0, 2], V[0, 3] = 0.0, -1.0, 0.0, 1.0
        V[1, 0], V[1, 1], V[1, 2], V[1, 3] = -ur, -uz, ur, uz
        V[2, 0], V[2, 1], V[2, 2], V[2, 3] = 0.5, 0.0, 0.5, 0.0
        for p in range(4):
            g[p] = Fz * V[0, p] + Fl * V[1, p] + Fm * V[2, p]
        if want_h:
            C[0, 0] = 2.0 * ci / (l * m)
            C[0, 1] = C[1, 0] = -2.0 * ci * dz / (l * l * m)
            C[0, 2] = C[2, 0] = -2.0 * ci * dz / (l * m * m)
            C[1, 1] = 2.0 * F / (l * l)
            C[1, 2] = C[2, 1] = F / (l * m)
            C[2, 2] = 2.0 * F / (m * m)
            for p in range(4):
                for s in range(p + 1):
                    acc = 0.0
                    for a in range(3):
                        for b in range(3):
                            acc += V[a, p] * C[a, b] * V[b, s]
                    H[p, s] = acc
            add_length_hessian(H, 0, Fl, ur, uz, l)
        add_local(grad, hb, 2 * i, g, H, 4, want_h)
    return E


def energy(r, z, coef) -> float:
    return _kernel(r, z, coef[0], NO_GRADIENT, NO_HESSIAN, False, False)


def accumulate(r, z, coef, grad, hb) -> float:
    """Add the gradient (and the Hessian if ``hb`` has columns) into grad / hb; return E."""
    return _kernel(r, z, coef[0], grad, hb, True, hb.shape[1] > 0)


def term(strength: float) -> Term:
    """The hoop bending term with weight H = ``strength``. Its ``energy`` and ``accumulate`` are
    this module's functions for every strength (the solver's fused energy recognizes them)."""
    def coefficients(grid):
        return (strength * segment_weights(grid) / grid.n_nodes,)

    return Term("hoop_bending", stencil=2, offset=0, coefficients=coefficients, energy=energy,
                accumulate=accumulate)
