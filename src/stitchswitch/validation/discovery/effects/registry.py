"""The library of candidate effects: what an effect is, and the registry.

An effect is a named, documented modification of the reduced model with one or two parameters
whose all-zero values are the starting model exactly. It may change any of three things, each
optional:

* ``material(material, values) -> Material``: a material field (``prestretch_loss``: eta);
* ``grid(grid, patch, material, values) -> Grid``: the per-segment rest metric and stiffnesses
  (``fill_exponent``, ``boundary_transition``);
* ``terms(patch, material, values) -> tuple``: extra energy terms, each a
  ``reduced.model.terms.Term`` whose kernel lives in ``reduced/model/terms/`` with its own
  finite-difference test (``hardening``, ``hoop_bending``, ``tension_asymmetry``); the effect
  maps its parameters to the term.

``stitchswitch.validation.discovery.effects.model.configure`` composes the active effects into a material
and a term tuple for ``reduced.solvers.solve.solve``. An effect whose parameters are all zero is left out
entirely, so at zero strength the solve is the starting model's, bit for bit.

Registering a new effect is one module ending in ``register_effect(Effect(...))`` plus its import
in ``effects/__init__.py`` (see docs/discovery.md).
"""
from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

from stitchswitch.errors import InvalidInputError

__all__ = ["EffectParameter", "Effect", "register_effect", "register_control", "get_effect",
           "resolve", "effect_names", "LIBRARY", "CONTROLS"]


@dataclass(frozen=True)
class EffectParameter:
    """One parameter of an effect. ``lower``/``upper``: bounds of the fit (0 inside them);
    ``probe``: the value used for the sensitivity signature and the scale of the search;
    ``signed``: the fit scans both signs; ``hidden``: the (low, high) interval of values drawn
    for hidden-effect datasets, chosen so that the part of the effect a recalibration of the
    starting model cannot absorb is comparable to the noise of the synthetic reference data
    (measured; docs/discovery.md)."""

    name: str
    unit: str
    lower: float
    upper: float
    probe: float
    hidden: tuple[float, float]
    signed: bool = False

    def __post_init__(self) -> None:
        if not (self.lower <= 0.0 <= self.upper and self.lower < self.upper):
            raise InvalidInputError(f"effect parameter {self.name}: bounds [{self.lower}, "
                                    f"{self.upper}] must contain 0")
        lo, hi = self.hidden
        if not self.lower <= lo <= hi <= self.upper:
            raise InvalidInputError(f"effect parameter {self.name}: hidden range {self.hidden} "
                                    "must lie inside the bounds")
        if not (self.lower <= self.probe <= self.upper and self.probe > 0.0):
            raise InvalidInputError(f"effect parameter {self.name}: probe {self.probe} must be "
                                    "positive and inside the bounds")


@dataclass(frozen=True)
class Effect:
    """A candidate effect; see the module docstring. ``summary``: one line for reports;
    ``physics``: what it models and how, for docs and the report."""

    name: str
    summary: str
    physics: str
    parameters: tuple[EffectParameter, ...]
    material: Callable | None = None
    grid: Callable | None = None
    terms: Callable | None = None

    def __post_init__(self) -> None:
        if not 1 <= len(self.parameters) <= 2:
            raise InvalidInputError(f"effect {self.name!r}: needs one or two parameters, "
                                    f"got {len(self.parameters)}")
        if self.material is None and self.grid is None and self.terms is None:
            raise InvalidInputError(f"effect {self.name!r}: changes nothing (no material, grid "
                                    "or terms function)")

    @property
    def parameter_names(self) -> tuple[str, ...]:
        return tuple(p.name for p in self.parameters)

    def values(self, values) -> tuple[float, ...]:
        """Validated parameter values (a sequence or a mapping by name) as a tuple."""
        if isinstance(values, dict):
            unknown = set(values) - set(self.parameter_names)
            if unknown:
                raise InvalidInputError(f"effect {self.name!r}: unknown parameter(s) "
                                        f"{', '.join(sorted(unknown))}")
            values = [values.get(n, 0.0) for n in self.parameter_names]
        values = tuple(float(v) for v in values)
        if len(values) != len(self.parameters):
            raise InvalidInputError(f"effect {self.name!r}: expected {len(self.parameters)} "
                                    f"value(s), got {len(values)}")
        for v, p in zip(values, self.parameters):
            if not math.isfinite(v) or not p.lower <= v <= p.upper:
                raise InvalidInputError(f"effect {self.name!r}, {p.name}: {v!r} is outside "
                                        f"[{p.lower:g}, {p.upper:g}] {p.unit}")
        return values

    @staticmethod
    def is_zero(values) -> bool:
        return all(v == 0.0 for v in values)


#: Registered effects by name, in registration order.
LIBRARY: dict[str, Effect] = {}
#: Control effects: solvable by name, but not candidates (they test for false discoveries).
CONTROLS: dict[str, Effect] = {}


def register_effect(effect: Effect) -> Effect:
    """Add ``effect`` to the library (a name may be registered once)."""
    if not isinstance(effect, Effect):
        raise InvalidInputError(f"register_effect: {effect!r} is not an Effect")
    if effect.name in LIBRARY and LIBRARY[effect.name] is not effect:
        raise InvalidInputError(f"effect {effect.name!r} is already registered")
    LIBRARY[effect.name] = effect
    return effect


def register_control(effect: Effect) -> Effect:
    """Make ``effect`` solvable by name without adding it to the candidate library."""
    if effect.name in LIBRARY:
        raise InvalidInputError(f"effect {effect.name!r} is already in the library")
    CONTROLS[effect.name] = effect
    return effect


def resolve(name: str) -> Effect:
    """A library effect or a control effect by name."""
    return CONTROLS[name] if name in CONTROLS else get_effect(name)


def get_effect(name: str) -> Effect:
    try:
        return LIBRARY[name]
    except KeyError:
        raise InvalidInputError(f"effect {name!r} is not in the library (known: "
                                f"{', '.join(LIBRARY)})") from None


def effect_names() -> tuple[str, ...]:
    return tuple(LIBRARY)
