"""Radial membrane term (Eq. 1 and the first part of Eq. 3), tension only.

    E_r = (1/N) sum_i k_r^(i) max(l_i - lambda_i, 0)^2 lambda_i R_{i+1},

l_i the deformed length of segment i and lambda_i its rest length, both in dR units.
A slack segment (l < lambda) costs nothing here: the compressive response in ``compression.py``
is what keeps it from collapsing.
"""
from __future__ import annotations

from numba import njit

from stitchswitch.reduced.model.terms.protocol import Term
from stitchswitch.reduced.model.terms.segment import add_segment, segment


def coefficients(grid):
    """(lambda, weight k_r lambda R_{i+1} / N) per segment."""
    return grid.lam, grid.k_r * grid.lam * grid.R[1:] / grid.n_nodes


@njit(cache=True)
def stretched(l, lam, w):
    """(stretched, E, dE/dl, d2E/dl2) of one segment of length l (rest length lam, weight w);
    a segment that is not stretched has no energy."""
    s = l - lam
    if s <= 0.0:
        return False, 0.0, 0.0, 0.0
    return True, w * s * s, 2.0 * w * s, 2.0 * w


@njit(cache=True)
def _kernel(r, z, lam, w, grad, hb, want_g, want_h):
    E = 0.0
    for i in range(r.size - 1):
        vr, vz, l = segment(r, z, i)
        active, e, d1, d2 = stretched(l, lam[i], w[i])
        if not active:
            continue
        E += e
        if want_g:
            add_segment(grad, hb, i, d1, d2, vr, vz, l, want_h)
    return E


TERM = Term.from_kernel("radial", stencil=2, offset=0, coefficients=coefficients, kernel=_kernel)
