"""The shell's own frozen parameters: the physics the reduced model does not have, and the mesh.

``ShellParams`` holds what the reduced model's ``Material`` does not say: the Poisson ratio,
the bending rigidity's source (the calibrated bending weights, or a thickness through the plate
relation D = A t^2 / 12), the natural curvature of the embroidered layer, the physics switches
of the model-error table, gravity, and the discretization. Every field is validated; lengths
carry ``_mm``, curvatures ``_per_mm``.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, fields, replace

from stitchswitch.errors import InvalidInputError

#: The physics switches the model-error table turns off one at a time.
SWITCHES = ("hoop_bending", "poisson", "relaxed_membrane", "natural_curvature")


@dataclass(frozen=True)
class ShellParams:
    """Physics and mesh of the shell of revolution (docs/fem-reference.md, "Parameters").

    ``nu``: Poisson ratio of membrane and bending (a knit: 0.3 assumed, not measured).
    ``thickness_mm``: None takes the bending rigidity from the material's calibrated bending
    weights; a thickness gives D = sqrt(A_s A_t) t^2 / 12 (plate relation) instead.
    ``kappa0_per_mm``: natural curvature of the embroidered layer (thread-tension asymmetry);
    > 0 curves it like the pop-up dome. ``hoop_bending``: bend the parallels (k_t) too.
    ``relaxed_membrane``: the bare knit carries no compression in any direction (tension field,
    Pipkin relaxation); off, it resists hoop compression fully, as the reduced model's knit.
    ``areal_weight_n_per_m2``: gravity (self weight, pulling to -z), with the force scale
    ``knit_stiffness_n_per_m`` (the bare knit's tensile membrane stiffness) converting it.
    ``elements_inside``: cubic Hermite elements on the patch; ``growth``: size ratio of
    successive elements outside; ``intorder``: Gauss quadrature order.
    """

    nu: float = 0.3
    thickness_mm: float | None = None
    kappa0_per_mm: float = 0.0
    hoop_bending: bool = True
    relaxed_membrane: bool = True
    areal_weight_n_per_m2: float = 0.0
    knit_stiffness_n_per_m: float = 200.0
    elements_inside: int = 40
    growth: float = 1.08
    intorder: int = 6

    def __post_init__(self) -> None:
        for f in fields(self):
            v = getattr(self, f.name)
            if f.name in ("hoop_bending", "relaxed_membrane"):
                if not isinstance(v, bool):
                    raise InvalidInputError(f"{f.name}: {v!r} is not true or false")
                continue
            if v is None:
                continue
            if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
                raise InvalidInputError(f"{f.name}: {v!r} is not a finite number")
        if not -1.0 < self.nu <= 0.5:
            raise InvalidInputError(f"nu: {self.nu!r} is outside (-1, 0.5]")
        if self.thickness_mm is not None and not 0.0 < self.thickness_mm <= 10.0:
            raise InvalidInputError(f"thickness_mm: {self.thickness_mm!r} is outside (0, 10]")
        if not abs(self.kappa0_per_mm) <= 1.0:
            raise InvalidInputError(f"kappa0_per_mm: {self.kappa0_per_mm!r} is outside [-1, 1]")
        if self.areal_weight_n_per_m2 < 0:
            raise InvalidInputError(f"areal_weight_n_per_m2: {self.areal_weight_n_per_m2!r} must be >= 0")
        if self.knit_stiffness_n_per_m <= 0:
            raise InvalidInputError(f"knit_stiffness_n_per_m: {self.knit_stiffness_n_per_m!r} must be > 0")
        if not (isinstance(self.elements_inside, int) and 4 <= self.elements_inside <= 2000):
            raise InvalidInputError(f"elements_inside: {self.elements_inside!r} is not an integer in [4, 2000]")
        if not 1.0 <= self.growth <= 2.0:
            raise InvalidInputError(f"growth: {self.growth!r} is outside [1, 2]")
        if not (isinstance(self.intorder, int) and 4 <= self.intorder <= 12):
            raise InvalidInputError(f"intorder: {self.intorder!r} is not an integer in [4, 12]")

    def without(self, switch: str) -> "ShellParams":
        """The same shell with one physics switch of ``SWITCHES`` turned off."""
        if switch == "hoop_bending":
            return replace(self, hoop_bending=False)
        if switch == "poisson":
            return replace(self, nu=0.0)
        if switch == "relaxed_membrane":
            return replace(self, relaxed_membrane=False)
        if switch == "natural_curvature":
            return replace(self, kappa0_per_mm=0.0)
        raise InvalidInputError(f"switch: {switch!r} is not one of {', '.join(SWITCHES)}")

    def reduced_like(self) -> "ShellParams":
        """Every switch off: the shell with the reduced model's physics (its continuum limit up
        to the documented differences of formulation)."""
        out = self
        for s in SWITCHES:
            out = out.without(s)
        return out


DEFAULT_SHELL = ShellParams()
