"""The boundary node's ring, integrated by the trapezoid rule (a second-order quadrature).

The hoop (Eq. 2-3) and hardening (Eq. 5) integrands are evaluated at the nodes, and node i+1
takes the coefficients of segment i (the paper's indexing). On the embroidery boundary node
N_in that gives the node's whole ring the patch's values, although the integrand jumps there:
the quadrature of the ring is first order in dR, and r_a converges at first order (at d 90 mm,
p 1.0: 32.01 / 31.55 / 31.31 / 31.20 mm at N = 150 / 300 / 600 / 1200).

The trapezoid rule gives the boundary node half of each side's integrand. This term is the
correction that turns the paper's quadrature into that rule, at the one node where they differ:

    E_ring = 1/2 [ k_out eps_out^2 / (lambda_out R) - k_in eps_in^2 / (lambda_in R) ] / N
             + 1/2 w_log [ h(eps_out) - h(eps_in) ] / N,      eps = r_{N_in} - lambda R,

so the default ``ALL_TERMS`` (which includes it) is the model with the trapezoid rule, and
``variants.PAPER_INDEXING`` (with ``OFF`` in its place) the printed quadrature.
With it r_a converges at about second order (31.061 / 31.081 / 31.086 / 31.086 mm at the same
design and N; tests/test_convergence.py). Each element is a (node, rest radius, hoop weight,
hardening weight) with signed weights; the sum with the terms it corrects is the trapezoid rule,
whose Hessian is that of a sum of convex terms.
"""
from __future__ import annotations

import dataclasses

import numpy as np
from numba import njit

from stitchswitch.reduced.model.terms.hardening import h_scalar
from stitchswitch.reduced.model.terms.protocol import Term


@njit(cache=True)
def _kernel(r, z, node, rest, c, a, gamma, grad, hb, want_g, want_h):
    """``Term.from_kernel``'s signature; z does not enter. Element k acts on node ``node[k]``."""
    E = 0.0
    for k in range(node.size):
        n = node[k]
        e = r[n] - rest[k]
        v, d1, d2 = h_scalar(e, gamma)
        E += c[k] * e * e + a[k] * v
        if want_g:
            grad[2 * n] += 2.0 * c[k] * e + a[k] * d1
            if want_h:
                hb[0, 2 * n] += 2.0 * c[k] + a[k] * d2
    return E


def coefficients(grid):
    """Two elements on the boundary node N_in: + half the outside ring, - half the inside ring
    (the inside ring is what ``circumferential`` and ``hardening`` give that node)."""
    n, N = grid.n_inside, grid.n_nodes
    lam = np.array([grid.lam[n], grid.lam[n - 1]])          # outside, inside
    k = np.array([grid.k_theta[n], grid.k_theta[n - 1]])
    sign = np.array([0.5, -0.5])
    rest = lam * n
    return (np.full(2, n, dtype=np.int64), rest, sign * k / (rest * N),
            sign * grid.w_log / N, grid.gamma)


def _no_elements(grid):
    """No correction: the paper's quadrature (the same kernel, so the compiled path applies)."""
    return (np.zeros(0, dtype=np.int64), np.zeros(0), np.zeros(0), np.zeros(0), grid.gamma)


TERM = Term.from_kernel("boundary_ring", stencil=1, offset=0, coefficients=coefficients, kernel=_kernel)
#: The term switched off: every node's ring takes its segment's values, as printed.
OFF = dataclasses.replace(TERM, name="boundary_ring_off", coefficients=_no_elements)
