"""Discretization variants, used to measure where the reduced model's error comes from
(``fem_reference.check``, tests/test_convergence.py). Not used by default.

``hoop_node_average`` and ``hardening_node_average``: the circumferential strain of node i+1
with the rest metric and stiffness averaged over its two segments, instead of the paper's
"segment i's values at node i+1" (which puts the boundary node's ring fully inside the patch).

``PAPER_INDEXING``: the model with ``boundary_ring.OFF``, i.e. the boundary node's whole ring
inside the patch as printed: first-order convergence of r_a (the default trapezoid rule is
second order; tests/test_convergence.py).
"""
from __future__ import annotations

import dataclasses

import numpy as np

from stitchswitch.reduced.model.terms import (
    ALL_TERMS,
    bending,
    boundary_ring,
    circumferential,
    compression,
    hardening,
    radial,
)


def _node_average(a: np.ndarray) -> np.ndarray:
    out = np.array(a, dtype=float)
    out[:-1] = 0.5 * (a[:-1] + a[1:])
    return out


def _hoop_coefficients(grid):
    lam, k = _node_average(grid.lam), _node_average(grid.k_theta)
    rest = lam * grid.R[1:]
    return rest, k / (rest * grid.n_nodes)


def _hardening_coefficients(grid):
    return _node_average(grid.lam) * grid.R[1:], grid.gamma, grid.w_log / grid.n_nodes


hoop_node_average = dataclasses.replace(circumferential.TERM, name="circumferential_node_average",
                                        coefficients=_hoop_coefficients)
hardening_node_average = dataclasses.replace(hardening.TERM, name="hardening_node_average",
                                             coefficients=_hardening_coefficients)

#: The full term set with the node-averaged hoop quadrature (instead of the trapezoid rule).
HOOP_NODE_AVERAGE_TERMS = (radial.TERM, compression.TERM, hoop_node_average, hardening_node_average,
                           boundary_ring.OFF, bending.TERM)

#: The model with the paper's first-order quadrature of the boundary node's ring.
PAPER_INDEXING = tuple(boundary_ring.OFF if t is boundary_ring.TERM else t for t in ALL_TERMS)
