"""Radial membrane term (Eq. 1 and the first part of Eq. 3), tension only.

    E_r = (1/N) sum_i k_r^(i) max(l_i - lambda_i, 0)^2 lambda_i R_{i+1},

l_i the deformed length of segment i and lambda_i its rest length, both in dR units.
A slack segment (l < lambda) costs nothing here: the regularization in ``compression.py``
is what keeps it from collapsing.
"""
from __future__ import annotations

import numpy as np

from stitchswitch.reduced.terms.segment import segment_hessian

STENCIL = 2
OFFSET = 0


def _weight(grid) -> np.ndarray:
    return grid.k_r * grid.lam * grid.R[1:] / grid.n_nodes


def energy(geo, grid) -> float:
    s = np.maximum(geo.l - grid.lam, 0.0)
    return float(np.sum(_weight(grid) * s * s))


def local(geo, grid, hessian: bool = True):
    a = _weight(grid)
    s = np.maximum(geo.l - grid.lam, 0.0)
    g = (2 * a * s)[:, None] * geo.length_gradient()
    H = segment_hessian(2 * a * (s > 0), 2 * a * s, geo) if hessian else None
    return a * s * s, g, H
