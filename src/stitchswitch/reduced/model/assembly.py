"""Sum the energy terms into a total energy, a gradient and a banded Hessian.

Global dofs are interleaved node by node: dof 2i is r_i and dof 2i+1 is z_i. Every term
couples at most three neighbouring nodes, so the Hessian has half-bandwidth 5 in this
ordering; it is returned in LAPACK lower band storage ``hb[k, j] = H[j + k, j]`` (6, 2N).
Every term is a ``terms.protocol.Term``; each term's compiled kernel adds its own contribution
in place (``terms/segment.py``), so the assembly loop is one call per term.
"""
from __future__ import annotations

from collections.abc import Iterable

import numpy as np

from stitchswitch.errors import InvalidInputError
from stitchswitch.reduced.model.discretization import Grid
from stitchswitch.reduced.model.terms import ALL_TERMS, Term
from stitchswitch.reduced.model.terms.segment import BANDWIDTH, NO_HESSIAN


def in_domain(r: np.ndarray, z: np.ndarray) -> bool:
    """The energy is defined for r_i > 0 (i >= 1) and finite coordinates."""
    return bool(np.isfinite(r).all() and np.isfinite(z).all() and (r[1:] > 0).all())


class Model:
    """The total energy of one design (a grid) as a sum of terms, coefficients precomputed."""

    def __init__(self, grid: Grid, terms: Iterable[Term] = ALL_TERMS):
        self.grid = grid
        self.terms = tuple(terms)
        for term in self.terms:
            if not isinstance(term, Term):
                raise InvalidInputError(f"terms: {term!r} is not a Term (reduced.model.terms.protocol)")
        self._coefs = [term.coefficients(grid) for term in self.terms]

    def energy(self, r: np.ndarray, z: np.ndarray) -> float:
        """Total energy; +inf outside the domain."""
        if not in_domain(r, z):
            return np.inf
        total = 0.0
        for term, coef in zip(self.terms, self._coefs):
            total += term.energy(r, z, coef)
        return total if np.isfinite(total) else np.inf

    def accumulate(self, r: np.ndarray, z: np.ndarray, grad: np.ndarray, hb: np.ndarray) -> float:
        """Add the gradient into ``grad`` (2N,) and, if ``hb`` has columns, the banded Hessian
        into ``hb`` (6, 2N), term by term in order; return the energy."""
        total = 0.0
        for term, coef in zip(self.terms, self._coefs):
            total += term.accumulate(r, z, coef, grad, hb)
        return total

    def derivatives(self, r: np.ndarray, z: np.ndarray, hessian: bool = True):
        """Energy, gradient (2N,) and banded Hessian (6, 2N) (None if ``hessian`` is False)."""
        n = 2 * self.grid.n_nodes
        grad = np.zeros(n)
        hb = np.zeros((BANDWIDTH + 1, n)) if hessian else NO_HESSIAN
        total = self.accumulate(r, z, grad, hb)
        return total, grad, (hb if hessian else None)

    def gradient(self, r: np.ndarray, z: np.ndarray) -> np.ndarray:
        return self.derivatives(r, z, hessian=False)[1]


def energy(r: np.ndarray, z: np.ndarray, grid: Grid, terms: Iterable[Term] = ALL_TERMS) -> float:
    """Total energy (Eq. 6 plus the compressive response and the boundary ring); +inf outside the domain."""
    return Model(grid, terms).energy(r, z)


def derivatives(r: np.ndarray, z: np.ndarray, grid: Grid, terms: Iterable[Term] = ALL_TERMS, hessian: bool = True):
    """Energy, gradient and banded Hessian; see ``Model.derivatives``."""
    return Model(grid, terms).derivatives(r, z, hessian)


def gradient(r: np.ndarray, z: np.ndarray, grid: Grid, terms: Iterable[Term] = ALL_TERMS) -> np.ndarray:
    """Gradient (2N,) in interleaved dofs (no Hessian work)."""
    return Model(grid, terms).gradient(r, z)


def band_to_dense(hb: np.ndarray) -> np.ndarray:
    """Dense symmetric matrix from lower band storage; for tests and small problems."""
    n = hb.shape[1]
    H = np.zeros((n, n))
    for k in range(hb.shape[0]):
        idx = np.arange(n - k)
        H[idx + k, idx] = hb[k, : n - k]
        H[idx, idx + k] = hb[k, : n - k]
    return H
