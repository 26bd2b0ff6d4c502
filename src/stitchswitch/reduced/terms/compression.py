"""Slack regularization: a weak compressive stiffness with a barrier at zero length.

The printed model (Eq. 1) gives slack segments no stiffness at all. Its infimum then can have
a segment outside the embroidery collapsed to zero length (a perfect fold): the energy keeps
dropping as that length goes to 0 and no minimizer exists (docs/model.md). We add, per
segment, with t = l / lambda and c = ``Material.compression_ratio``:

    E_c = (1/N) sum_i c k_r^(i) lambda_i^3 R_{i+1} psi(t_i),
    psi(t) = 2 (t - 1 - ln t) for t < 1, 0 otherwise.

psi(1) = psi'(1) = 0 and psi''(1) = 2, so near the rest length E_c is the radial term with
stiffness c k_r acting on compression; psi -> infinity as t -> 0, so no segment collapses
and the problem has a true minimizer. c -> 0 recovers the printed model (tested: the
keypoints converge as c decreases).
"""
from __future__ import annotations

import numpy as np

from stitchswitch.reduced.terms.segment import segment_hessian

STENCIL = 2
OFFSET = 0


def _weight(grid) -> np.ndarray:
    return grid.compression * grid.k_r * grid.lam ** 3 * grid.R[1:] / grid.n_nodes


def _psi(t):
    """psi(t), psi'(t), psi''(t); zero for t >= 1."""
    ts = np.minimum(t, 1.0)
    return 2.0 * (ts - 1.0 - np.log(ts)), 2.0 * (1.0 - 1.0 / ts), np.where(t < 1.0, 2.0 / (ts * ts), 0.0)


def energy(geo, grid) -> float:
    if np.any(geo.l <= 0):
        return np.inf
    psi, _, _ = _psi(geo.l / grid.lam)
    return float(np.sum(_weight(grid) * psi))


def local(geo, grid, hessian: bool = True):
    a = _weight(grid)
    psi, dpsi, d2psi = _psi(geo.l / grid.lam)
    c1 = a * dpsi / grid.lam
    g = c1[:, None] * geo.length_gradient()
    H = segment_hessian(a * d2psi / grid.lam ** 2, c1, geo) if hessian else None
    return a * psi, g, H
