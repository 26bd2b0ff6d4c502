"""Circumferential membrane term (Eq. 2 and the second part of Eq. 3).

    eps_i = r_{i+1} - lambda_i R_{i+1}            (dR units, Eq. 2)
    E_t = (1/N) sum_i k_theta^(i) eps_i^2 / (lambda_i R_{i+1})

eps_i / (lambda_i R_{i+1}) is the hoop strain of the ring through node i+1, so each term is
that strain squared times the ring's rest circumference / 2 pi, like the radial term. Unlike
the radial term it resists compression too (the paper's Eq. 2 has no max). One element per
node i+1 (STENCIL = 1); only r_{i+1} enters.
"""
from __future__ import annotations

import numpy as np
from numba import njit

from stitchswitch.reduced.model.terms.protocol import Term


def strain(r, grid) -> np.ndarray:
    """eps_theta of Eq. 2 for nodes 1..N-1, dR units."""
    return r[1:] - grid.lam * grid.R[1:]


def coefficients(grid):
    """(rest ring radius lambda R_{i+1}, weight k_theta / (lambda R_{i+1} N)) per node i+1."""
    rest = grid.lam * grid.R[1:]
    return rest, grid.k_theta / (rest * grid.n_nodes)


@njit(cache=True)
def _kernel(r, z, rest, w, grad, hb, want_g, want_h):
    """``Term.from_kernel``'s signature; z does not enter."""
    E = 0.0
    for i in range(rest.size):
        eps = r[i + 1] - rest[i]
        E += w[i] * eps * eps
        if want_g:
            grad[2 * i + 2] += 2.0 * w[i] * eps
            if want_h:
                hb[0, 2 * i + 2] += 2.0 * w[i]
    return E


TERM = Term.from_kernel("circumferential", stencil=1, offset=1, coefficients=coefficients, kernel=_kernel)
