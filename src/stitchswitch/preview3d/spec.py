"""What the 3D preview shows: pieces, patches and the material, independent of the file format.

All lengths are garment coordinates in mm on the relaxed fabric, except ``diameter_mm``, which
is the model's diameter on the pre-stretched fabric (the design-file contract). ``spec_from_design``
reads a ``layout.garment.design.Design`` (or anything with the same attributes).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from stitchswitch.errors import InvalidInputError
from stitchswitch.reduced.model.params import DEFAULT_MATERIAL, Material

STATES = ("up", "down")


@dataclass(frozen=True, eq=False)
class PreviewPiece:
    """A flat garment piece: closed outline (n, 2) in mm, last point not repeated."""

    name: str
    outline_mm: np.ndarray


@dataclass(frozen=True, eq=False)
class PreviewPatch:
    """One patch: centre in garment mm, model diameter (pre-stretched mm) and fill, state.

    ``outline_mm`` (optional) is the non-circular outer outline, relative to the centre, on the
    stretched fabric; it is drawn as a line, the surface stays the circular model's."""

    id: str
    centre_mm: tuple[float, float]
    diameter_mm: float
    fill: float
    state: str = "up"
    outline_mm: np.ndarray | None = None

    def __post_init__(self) -> None:
        c = tuple(float(v) for v in self.centre_mm)
        if len(c) != 2 or not all(math.isfinite(v) for v in c):
            raise InvalidInputError(
                f"patch {self.id}: centre_mm {self.centre_mm!r} must be 2 finite numbers")
        object.__setattr__(self, "centre_mm", c)
        if self.state not in STATES:
            raise InvalidInputError(f"patch {self.id}: state {self.state!r} must be 'up' or 'down'")


@dataclass(frozen=True, eq=False)
class PreviewSpec:
    pieces: tuple[PreviewPiece, ...]
    patches: tuple[PreviewPatch, ...]
    material: Material = DEFAULT_MATERIAL

    def with_state(self, state: str) -> "PreviewSpec":
        """Every patch in ``state`` ("up" or "down"); "mixed" keeps each patch's own."""
        if state == "mixed":
            return self
        if state not in STATES:
            raise InvalidInputError(f"state: {state!r} must be 'up', 'down' or 'mixed'")
        patches = tuple(PreviewPatch(p.id, p.centre_mm, p.diameter_mm, p.fill, state, p.outline_mm)
                        for p in self.patches)
        return PreviewSpec(self.pieces, patches, self.material)


def spec_from_design(design) -> PreviewSpec:
    """The preview spec of a ``layout.garment.design.Design``."""
    pieces = tuple(PreviewPiece(p.name, np.asarray(p.outline_mm, dtype=float))
                   for p in design.pieces)
    patches = tuple(
        PreviewPatch(p.id, tuple(p.centre_mm), p.diameter_mm, p.fill, p.state,
                     None if getattr(p, "outline_mm", None) is None
                     else np.asarray(p.outline_mm, dtype=float))
        for p in design.patches)
    return PreviewSpec(pieces, patches, design.material_object())
