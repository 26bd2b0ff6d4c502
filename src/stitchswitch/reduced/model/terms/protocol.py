"""The one shape of an energy term: ``Term``.

Every term of the reduced model, every discretization variant and every term an effect adds is
a ``Term``. It works on the node coordinates (r_i, z_i) in units of dR:

* ``stencil`` (nodes per element) and ``offset`` (first node of the first element);
* ``coefficients(grid)``: its per-element coefficients for one design, computed once;
* ``energy(r, z, coef) -> float`` (+inf outside the term's domain);
* ``accumulate(r, z, coef, grad, hb) -> float``: adds its gradient into ``grad`` (2N,) and, if
  ``hb`` has columns, its Hessian into the lower band ``hb`` (6, 2N); returns its energy.

``energy`` and ``accumulate`` are thin wrappers of compiled kernels; the assembly calls them
directly, so a term costs one attribute look-up per evaluation. ``Term.from_kernel`` writes both
wrappers for a kernel of the common signature. A variant is
``dataclasses.replace(term, name=..., coefficients=...)``.
"""
from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

from stitchswitch.errors import InvalidInputError
from stitchswitch.reduced.model.terms.segment import BANDWIDTH, NO_GRADIENT, NO_HESSIAN

#: Most nodes one element may couple: the banded Hessian holds three-node stencils.
MAX_STENCIL = (BANDWIDTH + 1) // 2


@dataclass(frozen=True)
class Term:
    """One energy term; see the module docstring."""

    name: str
    stencil: int
    offset: int
    coefficients: Callable
    energy: Callable
    accumulate: Callable

    def __post_init__(self) -> None:
        if not 1 <= self.stencil <= MAX_STENCIL:
            raise InvalidInputError(f"term {self.name!r}: stencil {self.stencil} is not in "
                                    f"1..{MAX_STENCIL} (the Hessian's band)")
        if self.offset < 0:
            raise InvalidInputError(f"term {self.name!r}: offset {self.offset} is negative")

    @classmethod
    def from_kernel(cls, name: str, stencil: int, offset: int, coefficients: Callable,
                    kernel: Callable) -> "Term":
        """The term of a compiled ``kernel(r, z, *coef, grad, hb, want_g, want_h) -> E`` that adds
        its gradient (if ``want_g``) and Hessian (if ``want_h``) in place."""
        def energy(r, z, coef) -> float:
            return kernel(r, z, *coef, NO_GRADIENT, NO_HESSIAN, False, False)

        def accumulate(r, z, coef, grad, hb) -> float:
            return kernel(r, z, *coef, grad, hb, True, hb.shape[1] > 0)

        return cls(name, stencil, offset, coefficients, energy, accumulate)
