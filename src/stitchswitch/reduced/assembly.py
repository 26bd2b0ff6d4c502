"""Sum the energy terms into a total energy, a gradient and a sparse (banded) Hessian.

Global dofs are interleaved node by node: dof 2i is r_i and dof 2i+1 is z_i. Every term
couples at most three neighbouring nodes, so the Hessian has half-bandwidth 5 in this
ordering. ``hessian_coo`` returns it as coordinate triplets; the solver maps them onto its
reduced (constrained) variables and stores the result banded.
"""
from __future__ import annotations

from functools import lru_cache

import numpy as np

from stitchswitch.reduced.discretization import Grid
from stitchswitch.reduced.terms import ALL_TERMS
from stitchswitch.reduced.terms.segment import geometry


def in_domain(r: np.ndarray, z: np.ndarray) -> bool:
    """The energy is defined for r_i > 0 (i >= 1) and finite coordinates."""
    return bool(np.all(np.isfinite(r)) and np.all(np.isfinite(z)) and np.all(r[1:] > 0))


def energy(r: np.ndarray, z: np.ndarray, grid: Grid, terms=ALL_TERMS) -> float:
    """Total energy (Eq. 6 plus the slack regularization); +inf outside the domain."""
    if not in_domain(r, z):
        return np.inf
    geo = geometry(r, z)
    total = 0.0
    for term in terms:
        total += term.energy(geo, grid)
        if not np.isfinite(total):
            return np.inf
    return total


@lru_cache(maxsize=64)
def _stencil_index(n_nodes: int, stencil: int, offset: int):
    """Global dof of every local dof of every element, and COO row/col arrays."""
    count = n_nodes - stencil + 1 - offset
    first = 2 * (offset + np.arange(count))
    dofs = first[:, None] + np.arange(2 * stencil)[None, :]
    rows = np.repeat(dofs, 2 * stencil, axis=1).ravel()
    cols = np.tile(dofs, (1, 2 * stencil)).ravel()
    for a in (dofs, rows, cols):
        a.setflags(write=False)
    return dofs, rows, cols


def derivatives(r: np.ndarray, z: np.ndarray, grid: Grid, terms=ALL_TERMS, hessian: bool = True):
    """Energy, gradient (2N,) and Hessian triplets (rows, cols, vals) of the sum of terms
    (None instead of the triplets if ``hessian`` is False).

    Terms sharing a stencil are summed element-wise before they are scattered."""
    n = grid.n_nodes
    geo = geometry(r, z)
    by_stencil: dict[tuple[int, int], list] = {}
    total = 0.0
    for term in terms:
        e, g, H = term.local(geo, grid, hessian)
        total += float(np.sum(e))
        key = (term.STENCIL, term.OFFSET)
        if key in by_stencil:
            by_stencil[key][0] = by_stencil[key][0] + g
            by_stencil[key][1] = by_stencil[key][1] + H if hessian else None
        else:
            by_stencil[key] = [g, H]
    grad = np.zeros(2 * n)
    rows, cols, vals = [], [], []
    for (stencil, offset), (g, H) in by_stencil.items():
        dofs, rr, cc = _stencil_index(n, stencil, offset)
        grad += np.bincount(dofs.ravel(), g.ravel(), minlength=2 * n)
        if hessian:
            rows.append(rr)
            cols.append(cc)
            vals.append(H.ravel())
    if not hessian:
        return total, grad, None
    return total, grad, (np.concatenate(rows), np.concatenate(cols), np.concatenate(vals))


def gradient(r: np.ndarray, z: np.ndarray, grid: Grid, terms=ALL_TERMS) -> np.ndarray:
    """Gradient (2N,) in interleaved dofs (no Hessian work)."""
    return derivatives(r, z, grid, terms, hessian=False)[1]


def hessian_dense(r: np.ndarray, z: np.ndarray, grid: Grid, terms=ALL_TERMS) -> np.ndarray:
    """Dense (2N, 2N) Hessian; for tests and small problems only."""
    _, _, (rows, cols, vals) = derivatives(r, z, grid, terms)
    n = 2 * grid.n_nodes
    H = np.zeros((n, n))
    np.add.at(H, (rows, cols), vals)
    return H
