"""The patch's own weight: a potential energy linear in z.

    E_g = (g / N) sum_i m_i z_i,   m_i = R_i (1 + mu p^2 [node i in the patch]),

the ring mass of node i proportional to its rest radius, the embroidery mu times heavier per
rest area than the fabric at p = 1. The gradient is constant and the Hessian zero.
"""
from __future__ import annotations

import numpy as np
from numba import njit

from stitchswitch.reduced.model.terms.protocol import Term


@njit(cache=True)
def _kernel(z, m, grad, want_g):
    E = 0.0
    for i in range(z.size):
        E += m[i] * z[i]
        if want_g:
            grad[2 * i + 1] += m[i]
    return E


def energy(r, z, coef) -> float:
    return _kernel(z, coef[0], np.empty(0), False)


def accumulate(r, z, coef, grad, hb) -> float:
    """Add the gradient into ``grad`` (the Hessian is zero); return E."""
    return _kernel(z, coef[0], grad, True)


def term(g: float, fill: float, mass_ratio: float) -> Term:
    """The weight term with gravity ``g`` for a patch of fill ``fill`` whose embroidery is
    ``mass_ratio`` times heavier than the fabric at p = 1."""
    def coefficients(grid):
        node_inside = np.arange(grid.n_nodes) <= grid.n_inside
        m = grid.R * (1.0 + mass_ratio * fill ** 2 * node_inside)
        return (np.ascontiguousarray(g * m / grid.n_nodes),)

    return Term("gravity", stencil=1, offset=0, coefficients=coefficients, energy=energy,
                accumulate=accumulate)
