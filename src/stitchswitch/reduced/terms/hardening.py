"""Hardening of the knit near its stretch limit (Eq. 5), with the sign corrected.

As printed, f(e) = (e - g) log((g - e)/g) - e has f'' = -1/(g - e) < 0: with w_log > 0 it is
concave and rewards stretching. The hardening the paper describes is its negative,

    h(e) = (g - e) log(1 - e/g) + e,   h(0) = h'(0) = 0,   h'(e) = -log(1 - e/g),
    h''(e) = 1 / (g - e) > 0,           h(e) ~ e^2 / (2 g) for small e,

applied to the circumferential strain e = eps_theta of Eq. 2 (dR units, like g = gamma_dr):

    E_log = (w_log / N) sum_i h(eps_i).

h(g) = g is finite, so h is no barrier, and log(1 - e/g) is undefined for e >= g. Past
e* = (1 - CUTOFF) g we continue h by its second-order Taylor polynomial at e*, which is C2
and convex: the stiffness stays at h''(e*) = 1 / (CUTOFF g) for every larger strain.
"""
from __future__ import annotations

import numpy as np

from stitchswitch.reduced.terms.circumferential import strain

STENCIL = 1
OFFSET = 1

#: Fraction of gamma below the limit where the quadratic continuation takes over.
CUTOFF = 0.01


def h(e: np.ndarray, gamma: float):
    """h, h', h'' of the corrected hardening function, C2-continued past (1 - CUTOFF) gamma."""
    e = np.asarray(e, dtype=float)
    es = (1.0 - CUTOFF) * gamma
    ec = np.minimum(e, es)
    lg = np.log1p(-ec / gamma)
    v, d1, d2 = (gamma - ec) * lg + ec, -lg, 1.0 / (gamma - ec)
    over = e > es
    dx = np.where(over, e - es, 0.0)
    return (v + d1 * dx + 0.5 * d2 * dx * dx, d1 + d2 * dx, d2)


def energy(geo, grid) -> float:
    if grid.w_log == 0.0:
        return 0.0
    v, _, _ = h(strain(geo.r, grid), grid.gamma)
    return float(grid.w_log / grid.n_nodes * np.sum(v))


def local(geo, grid, hessian: bool = True):
    eps = strain(geo.r, grid)
    a = grid.w_log / grid.n_nodes
    v, d1, d2 = h(eps, grid.gamma)
    g = np.zeros((eps.size, 2))
    g[:, 0] = a * d1
    H = None
    if hessian:
        H = np.zeros((eps.size, 2, 2))
        H[:, 0, 0] = a * d2
    return a * v, g, H
