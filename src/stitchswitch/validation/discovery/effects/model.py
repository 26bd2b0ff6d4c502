"""Compose active effects into what ``reduced.solvers.solve.solve`` takes: a material and energy terms.

``configure(patch, material, active)`` with ``active`` = {effect name: parameter values}:

1. effects with all-zero values are dropped (so zero strength is the starting model bit for bit:
   the solve gets the unchanged material and ``terms=None``);
2. material changes are applied in the order of ``active``;
3. grid changes (rest metric, stiffnesses) are composed into one function, applied to the grid
   of every term through a thin wrapper (a ``Term`` with other coefficients, the idiom of
   ``reduced.model.terms.variants``): the solver, the continuation and the keypoints are untouched.
   The function keeps its last result, so the terms asking in turn for the same grid (the
   solver's coefficients, once per Newton start) share one transformed grid;
4. extra terms are appended to ``terms.ALL_TERMS``.

``solve_effects(patch, material, active)`` is ``solve`` on the result.
"""
from __future__ import annotations

import dataclasses

from stitchswitch.reduced.model.params import Material, Patch
from stitchswitch.reduced.model.terms import ALL_TERMS, Term
from stitchswitch.validation.discovery.effects.registry import resolve

__all__ = ["configure", "solve_effects", "with_grid"]


def with_grid(term: Term, transform) -> Term:
    """``term`` with ``transform(grid)`` applied before its coefficients are computed."""
    return dataclasses.replace(term, coefficients=lambda grid: term.coefficients(transform(grid)))


def configure(patch: Patch, material: Material, active) -> tuple[Material, tuple | None]:
    """(material, terms) of the model with the ``active`` effects (library or control effects by
    name); terms is None when no effect changes the energy or the grid (then ``solve`` uses its
    default terms)."""
    items = [(resolve(name), resolve(name).values(values)) for name, values in dict(active).items()]
    items = [(e, v) for e, v in items if not e.is_zero(v)]
    for effect, values in items:
        if effect.material is not None:
            material = effect.material(material, values)
    transforms = [(e.grid, v) for e, v in items if e.grid is not None]
    extra = tuple(t for e, v in items if e.terms is not None for t in e.terms(patch, material, v))
    if not transforms and not extra:
        return material, None

    last = []                  # (grid, transformed): every term asks for the same grid

    def transform(grid):
        if last and last[0] is grid:
            return last[1]
        out = grid
        for fn, values in transforms:
            out = fn(out, patch, material, values)
        last[:] = (grid, out)
        return out

    terms = ALL_TERMS + extra
    if transforms:
        terms = tuple(with_grid(t, transform) for t in terms)
    return material, terms


def solve_effects(patch: Patch, material: Material, active, **kw):
    """``reduced.solvers.solve.solve`` of ``patch`` with the ``active`` effects added to ``material``."""
    from stitchswitch.reduced.solvers.solve import solve

    material, terms = configure(patch, material, active)
    return solve(patch, material, terms=terms, **kw)
