"""Hardening of the knit near its stretch limit (Eq. 5), with the sign corrected.

As printed, f(e) = (e - g) log((g - e)/g) - e has f'' = -1/(g - e) < 0: with w_log > 0 it is
concave and rewards stretching. The hardening the paper describes is its negative,

    h(e) = (g - e) log(1 - e/g) + e,   h(0) = h'(0) = 0,   h'(e) = -log(1 - e/g),
    h''(e) = 1 / (g - e) > 0,           h(e) ~ e^2 / (2 g) for small e,

applied to the circumferential strain e = eps_theta of Eq. 2 (dR units, like g = gamma_mm / dR):

    E_log = (w_log / N) sum_i h(eps_i).

h(g) = g is finite, so h is no barrier, and log(1 - e/g) is undefined for e >= g. Past
e* = (1 - CUTOFF) g we continue h by its second-order Taylor polynomial at e*, which is C2
and convex: the stiffness stays at h''(e*) = 1 / (CUTOFF g) for every larger strain. The
continuation is a numerical safeguard for Newton's iterates, not physics: the limit gamma is
calibrated, and no equilibrium of the default material reaches the cutoff anywhere on the design
map (``limit_ratio``; tests/test_default_material.py).

Why a displacement and not a strain. Eq. 2's eps_theta = r - lambda R is a length, so a large
ring reaches the limit at a smaller strain than a small one. We keep the printed form and fit
gamma with the other parameters: it is the paper's model, and with gamma fitted the term never
reaches its limit, so the difference between the two forms is a smooth change of the hoop
stiffness with d that only data on the stretch limit (which the keypoints do not resolve) could
settle.
"""
from __future__ import annotations

import dataclasses
import math

import numpy as np
from numba import njit

from stitchswitch.reduced.model.terms.protocol import Term

#: Fraction of gamma below the limit where the quadratic continuation takes over.
CUTOFF = 0.01


@njit(cache=True)
def h_scalar(e, gamma):
    """h(e), h'(e), h''(e) of the corrected hardening function, C2-continued past the cutoff."""
    es = (1.0 - CUTOFF) * gamma
    ec = min(e, es)
    lg = math.log1p(-ec / gamma)
    v, d1, d2 = (gamma - ec) * lg + ec, -lg, 1.0 / (gamma - ec)
    if e > es:
        dx = e - es
        v, d1 = v + d1 * dx + 0.5 * d2 * dx * dx, d1 + d2 * dx
    return v, d1, d2


def h(e, gamma: float):
    """Vectorized ``h_scalar``: arrays h, h', h''."""
    return np.vectorize(h_scalar, otypes=[float, float, float])(e, gamma)


@njit(cache=True)
def _kernel(r, z, rest, gamma, a, grad, hb, want_g, want_h):
    """``Term.from_kernel``'s signature; z does not enter."""
    E = 0.0
    if a == 0.0:
        return E
    for i in range(rest.size):
        v, d1, d2 = h_scalar(r[i + 1] - rest[i], gamma)
        E += a * v
        if want_g:
            grad[2 * i + 2] += a * d1
            if want_h:
                hb[0, 2 * i + 2] += a * d2
    return E


def coefficients(grid):
    """(rest ring radius lambda R_{i+1} per node i+1, gamma, w_log / N)."""
    return grid.lam * grid.R[1:], grid.gamma, grid.w_log / grid.n_nodes


TERM = Term.from_kernel("hardening", stencil=1, offset=1, coefficients=coefficients, kernel=_kernel)


def with_weight(w_log: float, gamma_mm: float) -> Term:
    """This term with its own weight ``w_log`` and limit ``gamma_mm`` (mm) instead of the
    grid's: an extra hardening on top of the model's own."""
    def coefficients(grid):
        return grid.lam * grid.R[1:], gamma_mm / grid.dr_mm, w_log / grid.n_nodes

    return dataclasses.replace(TERM, name="hardening_extra", coefficients=coefficients)


def limit_ratio(grid, r) -> float:
    """The largest eps_theta / gamma over the nodes of a profile with radii ``r`` (dR units):
    below 1 - CUTOFF, no part of the energy comes from the quadratic continuation."""
    rest, gamma, _ = coefficients(grid)
    return float(np.max((np.asarray(r, dtype=float)[1:] - rest) / gamma))
