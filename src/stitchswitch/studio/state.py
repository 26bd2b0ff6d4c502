"""The studio's app state: the design being edited, the selection, and undo / redo.

The selection is one patch (``selected``, the one the inspector shows) plus, for a multiple
selection, ``also_selected``; moving or removing the selection acts on all of them at once.

Every action returns nothing and replaces ``design`` with a validated copy (``design_io``'s
rules, the same as a design file's), pushing the previous design on the undo stack. A run of
edits of one field of one patch (a slider being dragged) is one undo step. ``changed`` is
incremented on every change so that views know when to redraw.
"""
from __future__ import annotations

import dataclasses
import math

import shapely

from stitchswitch.errors import InvalidInputError
from stitchswitch.layout.garment.design import Design
from stitchswitch.layout.garment.design_io import validate_design
from stitchswitch.layout.garment.placement import place_at

#: the patch a click adds when nothing is selected: the middle of the default map's domain
DEFAULT_DIAMETER_MM = 60.0
DEFAULT_FILL = 0.5
EDITABLE = ("diameter_mm", "fill", "state", "composite", "conductive")
HISTORY_LIMIT = 200


class StudioState:
    """The design under edit. ``design``: current ``Design``; ``selected``: a patch id or None."""

    def __init__(self, design: Design):
        self.design = validate_design(design)
        self.selected: str | None = None
        self.also_selected: tuple[str, ...] = ()
        self.changed = 0
        self._undo: list[tuple] = []       # (design, selected, also_selected)
        self._redo: list[tuple] = []
        self._last_edit: tuple | None = None

    # --- history ------------------------------------------------------------------------
    def _commit(self, design: Design, selected: str | None, coalesce: tuple | None = None,
                also: tuple = ()) -> None:
        design = validate_design(design)
        if coalesce is None or coalesce != self._last_edit:
            self._undo.append((self.design, self.selected, self.also_selected))
            del self._undo[:-HISTORY_LIMIT]
        self._redo.clear()
        self._last_edit = coalesce
        self.design, self.selected, self.also_selected = design, selected, tuple(also)
        self.changed += 1

    @property
    def can_undo(self) -> bool:
        return bool(self._undo)

    @property
    def can_redo(self) -> bool:
        return bool(self._redo)

    def undo(self) -> None:
        self._step(self._undo, self._redo)

    def redo(self) -> None:
        self._step(self._redo, self._undo)

    def _step(self, source: list, target: list) -> None:
        """Restore the last state of ``source``, keeping the current one on ``target``."""
        if not source:
            return
        target.append((self.design, self.selected, self.also_selected))
        self.design, self.selected, self.also_selected = source.pop()
        self._last_edit = None
        self.changed += 1

    # --- selection ----------------------------------------------------------------------
    def select(self, patch_id: str | None) -> None:
        """Select one patch (None: nothing), ending a multiple selection."""
        if patch_id is not None:
            self.design.patch(patch_id)          # a clear error for an unknown id
        self.selected, self.also_selected = patch_id, ()
        self._last_edit = None
        self.changed += 1

    def toggle_select(self, patch_id: str) -> None:
        """Add a patch to the selection (it becomes the inspector's), or take it out."""
        self.design.patch(patch_id)
        chosen = [p for p in self.selection if p != patch_id]
        if patch_id not in self.selection:
            chosen.append(patch_id)
        self.selected = chosen[-1] if chosen else None
        self.also_selected = tuple(chosen[:-1])
        self._last_edit = None
        self.changed += 1

    @property
    def selection(self) -> tuple[str, ...]:
        """Every selected patch id, the inspector's last."""
        return self.also_selected + ((self.selected,) if self.selected is not None else ())

    def selected_patch(self):
        return None if self.selected is None else self.design.patch(self.selected)

    # --- geometry helpers ---------------------------------------------------------------
    def piece_at(self, point_mm) -> str | None:
        """The name of the first piece whose outline contains ``point_mm``, or None."""
        pt = shapely.Point(float(point_mm[0]), float(point_mm[1]))
        for piece in self.design.pieces:
            if shapely.Polygon(piece.outline_mm).contains(pt):
                return piece.name
        return None

    def patch_at(self, point_mm) -> str | None:
        """The id of the topmost patch whose relaxed footprint (diameter d / eta) contains the
        point, or None."""
        eta = self.design.material_object().eta
        x, y = float(point_mm[0]), float(point_mm[1])
        for p in reversed(self.design.patches):
            if math.hypot(x - p.centre_mm[0], y - p.centre_mm[1]) <= p.diameter_mm / (2 * eta):
                return p.id
        return None

    # --- actions ------------------------------------------------------------------------
    def add_patch(self, centre_mm, diameter_mm: float | None = None, fill: float | None = None,
                  piece: str | None = None) -> str:
        """Place a patch at ``centre_mm`` on ``piece`` (default: the piece under the point) with
        the selected patch's design (default 60 mm, fill 0.5); it becomes the selection."""
        piece = piece or self.piece_at(centre_mm)
        if piece is None:
            raise InvalidInputError(f"({centre_mm[0]:.1f}, {centre_mm[1]:.1f}) mm is not on a piece")
        like = self.selected_patch()
        d = diameter_mm if diameter_mm is not None else (like.diameter_mm if like else DEFAULT_DIAMETER_MM)
        p = fill if fill is not None else (like.fill if like else DEFAULT_FILL)
        design = place_at(self.design, piece, (float(centre_mm[0]), float(centre_mm[1])), d, p)
        new_id = design.patches[-1].id
        self._commit(design, new_id)
        return new_id

    def move_patch(self, patch_id: str, centre_mm) -> None:
        """Move a patch; it moves to the piece under its new centre if there is one."""
        old = self.design.patch(patch_id)
        piece = self.piece_at(centre_mm) or old.piece
        new = old.replace(centre_mm=(float(centre_mm[0]), float(centre_mm[1])), piece=piece)
        also = tuple(p for p in self.selection if p != patch_id) if patch_id in self.selection else ()
        self._commit(self._with(new), patch_id, also=also)

    def edit_patch(self, patch_id: str, *, own_step: bool = False, **changes) -> None:
        """Change ``diameter_mm``, ``fill``, ``state``, ``composite`` (a ``CompositeSpec`` or
        None) or ``conductive`` (a selection such as ``ring:0`` or None) of a patch, validated
        as the design file is; repeated edits of the same field(s) of the same patch are one
        undo step unless ``own_step``."""
        bad = sorted(set(changes) - set(EDITABLE))
        if bad:
            raise InvalidInputError(f"{bad[0]!r} is not an editable patch field "
                                    f"(editable: {', '.join(EDITABLE)})")
        old = self.design.patch(patch_id)
        new = old.replace(**changes)
        if new == old:
            return
        key = None if own_step else (patch_id, tuple(sorted(changes)))
        self._commit(self._with(new), patch_id, coalesce=key,
                     also=self.also_selected if patch_id == self.selected else ())

    def remove_patch(self, patch_id: str) -> None:
        self.remove_patches((patch_id,))

    def remove_patches(self, patch_ids) -> None:
        """Remove several patches in one undo step."""
        gone = {self.design.patch(pid).id for pid in patch_ids}
        patches = [p for p in self.design.patches if p.id not in gone]
        kept = [pid for pid in self.selection if pid not in gone]
        self._commit(self.design.with_patches(patches), kept[-1] if kept else None,
                     also=tuple(kept[:-1]))

    def move_patches(self, patch_ids, dx_mm: float, dy_mm: float) -> None:
        """Move several patches by (dx, dy) mm in one undo step; each moves to the piece under
        its new centre if there is one."""
        self._commit(self.moved(patch_ids, dx_mm, dy_mm), self.selected, also=self.also_selected)

    def moved(self, patch_ids, dx_mm: float, dy_mm: float):
        """The design with those patches moved by (dx, dy) mm, each to the piece under its new
        centre if there is one (what ``move_patches`` commits; the canvas draws it while they
        are dragged)."""
        moved = {}
        for pid in patch_ids:
            old = self.design.patch(pid)
            c = (old.centre_mm[0] + float(dx_mm), old.centre_mm[1] + float(dy_mm))
            moved[pid] = old.replace(centre_mm=c, piece=self.piece_at(c) or old.piece)
        return self.design.with_patches([moved.get(p.id, p) for p in self.design.patches])

    def set_pieces(self, pieces) -> None:
        """Replace the pieces (another size of a graded pattern) in one undo step; every patch
        keeps its piece name and garment position, so each piece of the new size must have the
        name of a piece a patch is on (the check then judges the patches on the new outlines)."""
        names = {p.name for p in pieces}
        lost = [p for p in self.design.patches if p.piece not in names]
        if lost:
            raise InvalidInputError(f"patch {lost[0].id} is on piece {lost[0].piece!r}, which "
                                    "the new pieces do not have (" + ", ".join(sorted(names)) + ")")
        self._commit(dataclasses.replace(self.design, pieces=tuple(pieces)), self.selected,
                     also=self.also_selected)

    def _with(self, new) -> Design:
        return self.design.with_patches([new if p.id == new.id else p for p in self.design.patches])
