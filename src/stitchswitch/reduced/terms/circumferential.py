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

STENCIL = 1
OFFSET = 1


def strain(r, grid) -> np.ndarray:
    """eps_theta of Eq. 2 for nodes 1..N-1, dR units."""
    return r[1:] - grid.lam * grid.R[1:]


def _weight(grid) -> np.ndarray:
    return grid.k_theta / (grid.lam * grid.R[1:] * grid.n_nodes)


def energy(geo, grid) -> float:
    eps = strain(geo.r, grid)
    return float(np.sum(_weight(grid) * eps * eps))


def local(geo, grid, hessian: bool = True):
    eps = strain(geo.r, grid)
    a = _weight(grid)
    g = np.zeros((eps.size, 2))
    g[:, 0] = 2 * a * eps
    H = None
    if hessian:
        H = np.zeros((eps.size, 2, 2))
        H[:, 0, 0] = 2 * a
    return a * eps * eps, g, H
