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

``tension_field`` is the same kernel with the compressive response as physics (a stiffness
mixed by fill, a bare-fabric stiffness that may be zero, a jamming stretch and a numerical
floor); it is not the default yet (docs/model.md, "Compression as physics").
"""
from __future__ import annotations

import dataclasses
import math

import numpy as np
from numba import njit

from stitchswitch.errors import InvalidInputError
from stitchswitch.reduced.model.terms.protocol import Term
from stitchswitch.reduced.model.terms.segment import add_segment, segment


def coefficients(grid):
    """(lambda, weight c k_r lambda^3 R_{i+1} / N, jamming stretch 0) per segment."""
    return (grid.lam, grid.compression * grid.k_r * grid.lam ** 3 * grid.R[1:] / grid.n_nodes,
            np.zeros(grid.lam.size))


@njit(cache=True)
def _kernel(r, z, lam, w, jam, grad, hb, want_g, want_h):
    """psi of s = (t - jam) / (1 - jam) per slack segment: the barrier sits at the jamming
    stretch t = jam (0: at zero length, the slack regularization); s = t where jam = 0."""
    E = 0.0
    for i in range(r.size - 1):
        vr, vz, l = segment(r, z, i)
        if l <= 0.0:
            return math.inf
        t = l / lam[i]
        if t >= 1.0:
            continue
        a = 1.0 - jam[i]
        s = (t - jam[i]) / a
        if s <= 0.0:
            return math.inf
        E += w[i] * 2.0 * (s - 1.0 - math.log(s))
        if want_g:
            d1 = w[i] * 2.0 * (1.0 - 1.0 / s) / (a * lam[i])
            d2 = w[i] * 2.0 / (s * s * a * a * lam[i] * lam[i])
            add_segment(grad, hb, i, d1, d2, vr, vz, l, want_h)
    return E


TERM = Term.from_kernel("compression", stencil=2, offset=0, coefficients=coefficients, kernel=_kernel)


def tension_field(fill: float, c_emb: float, c_fab: float, jam: float, floor: float = 1e-7) -> Term:
    """The compressive response as physics instead of one ratio: a stitched triangle mat resists
    compression, bare knit wrinkles (a tension field) until its loops jam.

    Per segment, with the stiffness ratios mixed like the other coefficients,
    c = c_emb p^2 + c_fab (1 - p^2) inside and c_fab outside, plus ``floor`` (a purely
    numerical weight that keeps the barrier defined where c = 0), and the barrier at the
    jamming stretch t = ``jam`` (l / lambda >= jam): psi of s = (t - jam) / (1 - jam) weighted
    c (1 - jam)^2 k_r lambda^3 R / N, so that the stiffness at the rest length is c k_r as in
    ``TERM``. With jam > 0 the problem keeps a minimizer as ``floor`` -> 0 (the barrier becomes
    the hard constraint t >= jam) and the keypoints converge; with jam = 0 and c_fab = 0 a bare
    segment next to the patch collapses instead (docs/model.md)."""
    if not (0.0 <= jam < 1.0) or min(c_emb, c_fab, floor) < 0.0 or not 0.0 < fill <= 1.0:
        raise InvalidInputError(f"tension_field: jam {jam!r} must be in [0, 1), c_emb {c_emb!r}, "
                                f"c_fab {c_fab!r} and floor {floor!r} >= 0, fill {fill!r} in (0, 1]")
    p2 = fill * fill

    def coefficients(grid):
        c = np.where(grid.inside, c_emb * p2 + c_fab * (1.0 - p2), c_fab) + floor
        a = 1.0 - jam
        return (grid.lam, c * a * a * grid.k_r * grid.lam ** 3 * grid.R[1:] / grid.n_nodes,
                np.full(grid.lam.size, jam))

    return dataclasses.replace(TERM, name="tension_field", coefficients=coefficients)
