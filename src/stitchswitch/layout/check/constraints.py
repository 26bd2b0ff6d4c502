"""The constraint check (paper, section 5: "a constraint panel checks fabrication feasibility,
including hoop fit, minimum feature size, and proximity to fabric edges").

``check_design(design, limits)`` runs every rule of ``layout/check/rules`` and returns the violations,
rule by rule in the order of ``RULES``, patches in design order. Each violation names its rule,
its severity, the patches and pieces involved and the measured value against the limit (both in
mm). The rules and the derivation of the feature sizes are in docs/design-file.md.

The limits are assumptions, not measurements (the paper gives none); every one can be changed.
"""
from __future__ import annotations

import math
from dataclasses import asdict, dataclass, fields

from stitchswitch.errors import InvalidInputError
from stitchswitch.layout.check.rules import (
    edge,
    features,
    frame_conflict,
    geometry,
    hoop,
    hoopable,
    model_range,
    spacing,
)
from stitchswitch.layout.check.violation import Violation

__all__ = ["Violation", "CheckLimits", "check_design", "RULES"]

#: the rule modules of ``stitchswitch.layout.check.rules``, in report order
RULES = (model_range, geometry, edge, spacing, features, hoop, hoopable, frame_conflict)


@dataclass(frozen=True)
class CheckLimits:
    """Limits of the check. Garment lengths (relaxed fabric): ``seam_allowance_mm``,
    ``edge_clearance_mm``, ``min_spacing_mm``. Stitch lengths (hoop, stretched fabric):
    ``min_gap_mm``, ``min_side_mm``, ``hoop_margin_mm`` (None: each hoop's own margin from the
    machine catalogue) and ``resolution_mm``, the triangle side the patches are tessellated
    with (that of ``patch_design.geometry_for`` and of fabrication)."""
    seam_allowance_mm: float = 10.0
    edge_clearance_mm: float = 5.0
    min_spacing_mm: float = 5.0
    min_gap_mm: float = 0.3
    min_side_mm: float = 2.0
    hoop_margin_mm: float | None = None
    resolution_mm: float = 5.0

    def __post_init__(self):
        for f in fields(self):
            v = getattr(self, f.name)
            if v is None and f.name == "hoop_margin_mm":
                continue
            if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
                raise InvalidInputError(f"{f.name}: {v!r} is not a finite number")
            if v < 0:
                raise InvalidInputError(f"{f.name}: {v!r} must be >= 0")
            object.__setattr__(self, f.name, float(v))
        if self.resolution_mm <= 0:
            raise InvalidInputError(f"resolution_mm: {self.resolution_mm!r} must be > 0")

    def as_dict(self) -> dict:
        return asdict(self)


def check_design(design, limits: CheckLimits = CheckLimits()) -> list[Violation]:
    """Every violation of ``design`` against ``limits``. The design is validated first (by
    the design file's rules), so a design built in code gets the loader's clear errors."""
    from stitchswitch.layout.garment.design_io import validate_design

    design = validate_design(design)
    eta = design.material_object().eta
    out: list[Violation] = []
    for rule in RULES:
        out.extend(rule.check(design, limits, eta))
    return out
