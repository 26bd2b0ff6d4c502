"""Small pieces: patches whose tessellation at the check's resolution has pieces under
``stitches.SMALL_PIECE_AREA_MM2`` (boundary slivers, or a core too fine for the triangle side).
They are sewn, so this is a warning, not a violation (``check`` keeps its exit code); it is the
same count and the same words as ``fabricate``'s sheet (``small_pieces`` in fabrication.json:
the hooping's sum of its patches' counts) and ``patch``'s notes, from
``stitches.small_pieces`` on the geometry the check's other rules judge
(``rules.geometry.tessellated``).
"""
from __future__ import annotations

from dataclasses import dataclass

from stitchswitch.layout.check.rules.geometry import tessellated
from stitchswitch.layout.embroidery.stitches import SMALL_PIECE_AREA_MM2, small_pieces, small_pieces_text

__all__ = ["SmallPieces", "small_piece_warnings"]


@dataclass(frozen=True)
class SmallPieces:
    """Patch ``patch`` on piece ``piece`` has ``count`` stitched pieces under ``area_mm2``."""

    patch: str
    piece: str
    count: int
    area_mm2: float = SMALL_PIECE_AREA_MM2

    @property
    def message(self) -> str:
        return f"patch {self.patch}: {small_pieces_text(self.count)}"

    @property
    def line(self) -> str:
        """The warning as ``stitchswitch check`` prints it (and the studio's panel shows it)."""
        return f"warning: {self.message}"

    def as_dict(self) -> dict:
        return {"patch": self.patch, "piece": self.piece, "count": self.count,
                "area_mm2": self.area_mm2, "message": self.message}


def small_piece_warnings(design, limits) -> list[SmallPieces]:
    """The patches of ``design`` with small pieces at ``limits.resolution_mm``, in design order
    (a patch that cannot be tessellated is the geometry rule's violation, not listed here)."""
    counts = ((patch, small_pieces(g)) for patch, g in tessellated(design, limits.resolution_mm))
    return [SmallPieces(patch.id, patch.piece, n) for patch, n in counts if n]
