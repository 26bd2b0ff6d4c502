"""The compressive response of the fabric: stitched mats resist compression, bare knit wrinkles
until its loops jam.

The printed model (Eq. 1) gives slack segments no stiffness at all. Its infimum then can have
a segment outside the embroidery collapsed to zero length (a perfect fold): the energy keeps
dropping as that length goes to 0 and no minimizer exists (docs/model.md). A stitched triangle
is a dense thread mat that resists compression in proportion to the stitched area; bare knit
buckles out of its plane at almost no cost (a tension field) until its loops touch, and a
jammed knit resists further compression like a solid. Per segment, with t = l / lambda:

    E_c = (1/N) sum_i k_r^(i) lambda_i R_{i+1} [ c_i lambda_i^2 psi(t_i)
                                                  + c_jam (j lambda_i - l_i)_+^2 ],
    psi(t) = 2 (t - 1 - ln t) for t < 1, 0 otherwise,
    c = c_emb p^2 + c_fab (1 - p^2) inside, c_fab outside, plus ``compression_floor``,

with j = ``Material.jam`` the jamming stretch and c_jam = ``Material.c_jam`` the jammed knit's
compressive stiffness as a ratio of its tensile one (the second bracket is the radial term's
form, mirrored at t = j). psi(1) = psi'(1) = 0 and psi''(1) = 2, so below the rest length the
stiffness is c k_r; psi -> infinity as t -> 0, so no segment has zero length and a minimizer
exists. The jamming penalty, not psi, is what holds a bare segment up where c_fab = 0: the
floor only matters near t = 0, which the penalty keeps the equilibrium far from, so the keypoints
converge as the floor goes to 0 (tests/test_compression.py). Without jamming (c_jam = 0) and
c_fab = 0 it is the printed model's collapse (``Material`` refuses it). Both parts are smooth
(the penalty C1 with a jump of its curvature at t = j, like the tension-only radial term at
t = 1), so Newton's method sees no barrier to crawl along. The energy is +inf for a segment of
zero length.
"""
from __future__ import annotations

import math

from numba import njit

from stitchswitch.reduced.model.terms.protocol import Term
from stitchswitch.reduced.model.terms.segment import add_segment, segment


def coefficients(grid):
    """(lambda, weight c k_r lambda^3 R_{i+1} / N, jammed length j lambda, weight
    c_jam k_r lambda R_{i+1} / N) per segment."""
    base = grid.k_r * grid.lam * grid.R[1:] / grid.n_nodes
    return grid.lam, grid.compression * grid.lam ** 2 * base, grid.jam * grid.lam, grid.c_jam * base


@njit(cache=True)
def slack(l, lam, w, jammed, wj):
    """(slack, jammed, E_psi, E_jam, dE/dl, d2E/dl2) of one segment of length l > 0: psi(l /
    lam) weighted ``w`` and, if l is below the jammed length, the penalty wj (jammed - l)^2
    (E_jam = 0 otherwise). A segment that is not slack has no energy."""
    t = l / lam
    if t >= 1.0:
        return False, False, 0.0, 0.0, 0.0, 0.0
    e = w * 2.0 * (t - 1.0 - math.log(t))
    d1 = w * 2.0 * (1.0 - 1.0 / t) / lam
    d2 = w * 2.0 / (t * t * lam * lam)
    g = jammed - l
    if g > 0.0:
        d1 -= 2.0 * wj * g
        d2 += 2.0 * wj
        return True, True, e, wj * g * g, d1, d2
    return True, False, e, 0.0, d1, d2


@njit(cache=True)
def _kernel(r, z, lam, w, jammed, wj, grad, hb, want_g, want_h):
    """psi(l / lambda) weighted ``w`` and the jamming penalty wj (jammed - l)_+^2 per slack
    segment."""
    E = 0.0
    for i in range(r.size - 1):
        vr, vz, l = segment(r, z, i)
        if l <= 0.0:
            return math.inf
        active, jam, e, e_jam, d1, d2 = slack(l, lam[i], w[i], jammed[i], wj[i])
        if not active:
            continue
        E += e
        if jam:
            E += e_jam
        if want_g:
            add_segment(grad, hb, i, d1, d2, vr, vz, l, want_h)
    return E


TERM = Term.from_kernel("compression", stencil=2, offset=0, coefficients=coefficients, kernel=_kernel)

