"""The parameters fitted by discrepancy discovery: the starting model's, plus one effect's.

A ``ModelSpec`` is the starting material, the names of its free coefficients (``BASE_FREE``),
the effects already added (``prior``, in forward selection) and optionally one candidate effect.
Its search vector x holds the free coefficients as log10 (bounds of
``reduced.calibration.evolution.BOUNDS``), then the prior effects' parameters, then the
candidate's, each divided by its probe value (so every coordinate is O(1)); ``offset`` is where
the candidate's parameters start. ``decode(x)`` gives the material and the active effects that
``effects.solve_effects`` takes.

Held fixed: ``k_theta_fab`` (the overall scale of the energy is not identifiable from shapes,
``reduced.calibration.evolution``) and ``w_log`` (the starting model's hardening is part of what is being
tested: the ``hardening`` effect adds to it), plus gamma, eta and the discretization.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from stitchswitch.errors import InvalidInputError
from stitchswitch.reduced.calibration.evolution import BOUNDS
from stitchswitch.reduced.model.params import Material
from stitchswitch.validation.discovery.effects import get_effect

__all__ = ["BASE_FREE", "ModelSpec", "BASE_STEP", "EFFECT_STEP"]

#: The starting model's coefficients refitted for every model (log10 scale).
BASE_FREE = ("w_b_emb", "w_b_fab", "k_r_emb", "k_r_fab", "k_theta_emb")
#: Forward finite-difference steps: log10 units for coefficients, probe units for effects.
BASE_STEP = 0.01
EFFECT_STEP = 0.05


@dataclass(frozen=True)
class ModelSpec:
    """The starting material, its free coefficients, and an optional candidate effect."""

    start: Material
    effect: str | None = None
    free: tuple = BASE_FREE
    prior: tuple = ()

    def __post_init__(self) -> None:
        for n in self.free:
            if n not in BOUNDS or BOUNDS[n][2] != "log":
                raise InvalidInputError(f"free coefficient {n!r} cannot be fitted here "
                                        f"(choose from {', '.join(BASE_FREE)})")
        if self.effect is not None:
            get_effect(self.effect)
        for name in self.prior:
            get_effect(name)
        if self.effect is not None and self.effect in self.prior:
            raise InvalidInputError(f"effect {self.effect!r} is already in the model")

    @property
    def label(self) -> str:
        return " + ".join(self.prior + ((self.effect,) if self.effect else ())) or "starting model"

    @property
    def effect_parameters(self):
        return get_effect(self.effect).parameters if self.effect else ()

    @property
    def prior_parameters(self):
        return tuple(p for name in self.prior for p in get_effect(name).parameters)

    @property
    def offset(self) -> int:
        """Index of the candidate's first parameter in x."""
        return len(self.free) + len(self.prior_parameters)

    @property
    def names(self) -> tuple[str, ...]:
        return (tuple(self.free) + tuple(p.name for p in self.prior_parameters) +
                tuple(p.name for p in self.effect_parameters))

    @property
    def size(self) -> int:
        return len(self.names)

    def bounds(self) -> tuple[np.ndarray, np.ndarray]:
        lo = [math.log10(BOUNDS[n][0]) for n in self.free]
        hi = [math.log10(BOUNDS[n][1]) for n in self.free]
        params = self.prior_parameters + tuple(self.effect_parameters)
        lo += [p.lower / p.probe for p in params]
        hi += [p.upper / p.probe for p in params]
        return np.array(lo), np.array(hi)

    def steps(self) -> np.ndarray:
        return np.array([BASE_STEP] * len(self.free) +
                        [EFFECT_STEP] * (self.size - len(self.free)))

    def encode(self, material: Material, effect_values=()) -> np.ndarray:
        """x of ``material`` (its free coefficients) and the effect's values (default zero; prior
        effects at zero)."""
        vals = tuple(effect_values) or (0.0,) * len(self.effect_parameters)
        x = [math.log10(getattr(material, n)) for n in self.free]
        x += [0.0] * len(self.prior_parameters)
        x += [v / p.probe for v, p in zip(vals, self.effect_parameters)]
        lo, hi = self.bounds()
        return np.clip(np.array(x, dtype=float), lo, hi)

    def decode(self, x) -> tuple[Material, dict]:
        """(material, {effect: values}) of the search vector ``x``."""
        x = np.asarray(x, dtype=float)
        k = len(self.free)
        material = self.start.replace(**{n: float(10.0 ** v) for n, v in zip(self.free, x[:k])})
        active, j = {}, k
        for name in self.prior + ((self.effect,) if self.effect else ()):
            params = get_effect(name).parameters
            active[name] = tuple(float(v * p.probe) for v, p in zip(x[j:j + len(params)], params))
            j += len(params)
        return material, active

    def with_effect(self, effect: str | None) -> "ModelSpec":
        return ModelSpec(self.start, effect, self.free, self.prior)

    def then(self, effect: str) -> "ModelSpec":
        """This model (its effect now a prior one) with the candidate ``effect`` added."""
        return ModelSpec(self.start, effect, self.free,
                         self.prior + ((self.effect,) if self.effect else ()))

    def extend(self, x_base: np.ndarray, effect_values) -> np.ndarray:
        """x of this (effect) spec from the base model's x (coefficients and prior effects)
        and the candidate's values."""
        k = self.offset
        tail = [v / p.probe for v, p in zip(effect_values, self.effect_parameters)]
        return np.concatenate([np.asarray(x_base, dtype=float)[:k], tail])

    def describe(self, x) -> dict:
        """{parameter name: value} in physical units (coefficients, then effect parameters)."""
        material, active = self.decode(x)
        out = {n: getattr(material, n) for n in self.free}
        for name, values in active.items():
            out.update(zip((p.name for p in get_effect(name).parameters), values))
        return out
