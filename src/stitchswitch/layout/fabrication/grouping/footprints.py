"""Patch footprints on the hooped (stretched) fabric: what hoop grouping works on.

The design file gives piece outlines and patch centres in relaxed garment mm, and the patch
diameter d on the pre-stretched fabric (design-file contract, docs/design-file.md). In the hoop
the fabric is stretched by eta (``material.eta``, 1.7) in both directions, so a patch's footprint
there is a disc of diameter d centred at eta times its garment centre, and a piece is its outline
scaled by eta. Composite and non-circular patches use the same disc: d is their bounding circle.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from stitchswitch.errors import InvalidInputError


@dataclass(frozen=True)
class Footprint:
    id: str
    piece: str
    centre_mm: tuple[float, float]   # stretched (hoop-scale) piece coordinates
    diameter_mm: float               # on the stretched fabric

    @property
    def radius_mm(self) -> float:
        return self.diameter_mm / 2.0


@dataclass(frozen=True, eq=False)
class StretchedPiece:
    name: str
    outline_mm: np.ndarray           # (n, 2) stretched piece coordinates, last point not repeated
    blank_mm: float = 0.0            # stretched mm the uncut blank extends past the outline


def stretch(design, eta: float, blank_margin_mm: float | None = None
            ) -> tuple[tuple[Footprint, ...], tuple[StretchedPiece, ...]]:
    """Footprints and pieces of a ``layout.garment.design.Design`` on fabric stretched by ``eta``.
    ``blank_margin_mm`` (relaxed mm; default the design's): how far each piece's uncut blank
    extends past its outline."""
    if not (math.isfinite(eta) and eta >= 1.0):
        raise InvalidInputError(f"stretch eta = {eta!r} must be a finite number >= 1")
    blank = design.blank_margin_mm if blank_margin_mm is None else float(blank_margin_mm)
    if not (math.isfinite(blank) and blank >= 0):
        raise InvalidInputError(f"blank margin {blank_margin_mm!r} mm must be a number >= 0")
    pieces = tuple(StretchedPiece(p.name, np.asarray(p.outline_mm, dtype=float) * eta,
                                  blank * eta) for p in design.pieces)
    feet = tuple(Footprint(p.id, p.piece, (p.centre_mm[0] * eta, p.centre_mm[1] * eta),
                           float(p.diameter_mm)) for p in design.patches)
    if not feet:
        raise InvalidInputError("the design has no patches: nothing to fabricate")
    return feet, pieces


def arrays(feet) -> tuple[np.ndarray, np.ndarray]:
    """(n, 2) centres and (n,) radii of footprints."""
    c = np.array([f.centre_mm for f in feet], dtype=float).reshape(-1, 2)
    r = np.array([f.radius_mm for f in feet], dtype=float)
    return c, r
