"""Slack regularization: a weak compressive stiffness with a barrier at zero length.

The printed model (Eq. 1) gives slack segments no stiffness at all. Its infimum then can have
a segment outside the embroidery collapsed to zero length (a perfect fold): the energy keeps
dropping as that length goes to 0 and no minimizer exists (docs/model.md). We add, per
segment, with t = l / lambda and c = ``Material.compression_ratio``:

    E_c = (1/N) sum_i c k_r^(i) lambda_i^3 R_{i+1} psi(t_i),
    psi(t) = 2 (t - 1 - ln t) for t < 1, 0 otherwise.

psi(1) = psi'(1) = 0 and psi''(1) = 2, so near the rest length E_c is the radial term with
stiffness c k_r acting on compression; psi -> infinity as t -> 0, so no segment collapses
and the problem has a true minimizer. c is a physical parameter, not a vanishing numerical
device: where the equilibrium is taut everywhere the term is inactive and the keypoints do
not depend on c, but where segments go slack h depends strongly on c (as c decreases the
slack segments shorten and the dome flattens; tests/test_solver.py, docs/model.md). The
energy is +inf for a segment of zero length.
"""
from __future__ import annotations

import math

from numba import njit

from stitchswitch.reduced.model.terms.protocol import Term
from stitchswitch.reduced.model.terms.segment import add_segment, segment


def coefficients(grid):
    """(lambda, weight c k_r lambda^3 R_{i+1} / N) per segment."""
    return grid.lam, grid.compression * grid.k_r * grid.lam ** 3 * grid.R[1:] / grid.n_nodes


@njit(cache=True)
def _kernel(r, z, lam, w, grad, hb, want_g, want_h):
    E = 0.0
    for i in range(r.size - 1):
        vr, vz, l = segment(r, z, i)
        if l <= 0.0:
            return math.inf
        t = l / lam[i]
        if t >= 1.0:
            continue
        E += w[i] * 2.0 * (t - 1.0 - math.log(t))
        if want_g:
            d1 = w[i] * 2.0 * (1.0 - 1.0 / t) / lam[i]
            d2 = w[i] * 2.0 / (t * t * lam[i] * lam[i])
            add_segment(grad, hb, i, d1, d2, vr, vz, l, want_h)
    return E


TERM = Term.from_kernel("compression", stencil=2, offset=0, coefficients=coefficients, kernel=_kernel)
