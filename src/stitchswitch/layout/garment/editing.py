"""Editing placed patches: move one, change its diameter, fill or piece, or remove patches.

Patch ids are stable: an edit keeps the patch's id and its place in the patch list, a removal
leaves every other id as it was, and nothing is renumbered. Every result is validated like a
design file (``design_io.validate_design``), with errors naming the patch by its id. Whether the
edited patch still fits, keeps its spacing and can be hooped is the constraint check's
business, as for placement.
"""
from __future__ import annotations

from stitchswitch.errors import InvalidInputError
from stitchswitch.layout.garment.design import Design
from stitchswitch.layout.garment.design_io import validate_design

__all__ = ["edit_patch", "remove_patches"]


def edit_patch(design: Design, patch_id: str, *, centre_mm=None, diameter_mm: float | None = None,
               fill: float | None = None, piece: str | None = None) -> Design:
    """A copy of ``design`` with patch ``patch_id`` changed (None leaves a field as it is)."""
    old = design.patch(patch_id)
    if piece is not None:
        design.piece(piece)                       # a clear error for an unknown piece
    changes = {}
    if centre_mm is not None:
        x, y = centre_mm
        changes["centre_mm"] = (float(x), float(y))
    if diameter_mm is not None:
        changes["diameter_mm"] = float(diameter_mm)
    if fill is not None:
        changes["fill"] = float(fill)
    if piece is not None:
        changes["piece"] = piece
    if not changes:
        raise InvalidInputError(f"patch {patch_id}: nothing to change")
    index = design.patches.index(old)
    patches = list(design.patches)
    patches[index] = old.replace(**changes)
    try:
        return validate_design(design.with_patches(patches), "edit")
    except InvalidInputError as exc:
        raise InvalidInputError(str(exc).replace(f"patches[{index}]", f"patch {patch_id}")) from None


def remove_patches(design: Design, patch_ids) -> Design:
    """A copy of ``design`` without the patches ``patch_ids`` (each must exist, once)."""
    ids = list(patch_ids)
    if not ids:
        raise InvalidInputError("no patch id to remove")
    seen = set()
    for pid in ids:
        if pid in seen:
            raise InvalidInputError(f"patch {pid} is named twice")
        seen.add(pid)
        design.patch(pid)                         # a clear error for an unknown id
    return validate_design(design.with_patches(p for p in design.patches if p.id not in seen),
                           "remove")
