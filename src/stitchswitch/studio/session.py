"""A studio session: the state, the document and everything the page shows, recomputed after
each action (the readout of the selected patch, the heights, the check, the 3D scene).

Actions raise ``InvalidInputError`` for a refused edit; the page shows its message and the
design stays as it was.
"""
from __future__ import annotations

import os
import time

from stitchswitch.errors import InvalidInputError
from stitchswitch.layout.fabrication.fabricate import FabricateOptions
from stitchswitch.layout.garment.design import CompositeSpec
from stitchswitch.layout.garment.piece_select import select_pieces
from stitchswitch.reduced.design_space.inverse import InverseTarget
from stitchswitch.studio import canvas, fabrication, inverse_panel, live_check, stitch_preview
from stitchswitch.studio.readout import heights_mm, readout
from stitchswitch.studio.state import StudioState


class Session:
    """``scene3d`` (a ``scene3d.Scene3D``) may be None (no 3D view). ``pattern``: the pieces
    of the graded pattern the design was started from (``dxf.reader.Piece``, every size), for
    the size picker; None otherwise. The check is rerun after
    every action (incrementally, ``live_check.LiveCheck``); the 3D scene is not: the page calls
    ``refresh_scene`` once it has shown the check, so the panel never waits for the scene."""

    def __init__(self, document, design, dmap, scene3d=None, pattern=None):
        self.document = document
        self.pattern = None if pattern is None else tuple(pattern)
        self.state = StudioState(design)
        self.dmap = dmap
        self.scene3d = scene3d
        self.checker = live_check.LiveCheck()
        self.violations: list = []
        self.small_pieces: list = []      # check's small-pieces warnings (not violations)
        self.candidates: list = []
        self.order = None
        self.order_mode = "garment"
        self.exported = None              # the last export's FabricationResult
        self.view_box = None              # the canvas's zoomed / panned view (None: fit)
        self.dragging: tuple = ()         # patches being dragged (their edge rule is drawn)
        self.drag_offset = None           # (dx, dy) mm the pointer has moved them (None: not yet)
        self.timings_s: dict = {}       # wall and CPU (process) time of the last check and scene
        #: True: an edit leaves the sidecar to ``write_autosave`` (the page writes it right after
        #: showing the edit, so the panel does not wait for the disk)
        self.autosave_later = False
        self._autosave_due = False
        self.refresh_check()

    @property
    def eta(self) -> float:
        return float(self.state.design.material_object().eta)

    # --- recomputation ------------------------------------------------------------------
    def refresh_check(self) -> None:
        t0, c0 = time.perf_counter(), time.process_time()
        self.violations = self.checker.run(self.state.design)
        self.small_pieces = self.checker.small       # the warnings check prints beside them
        self.timings_s["check_s"] = time.perf_counter() - t0
        self.timings_s["check_cpu_s"] = time.process_time() - c0

    def refresh_scene(self) -> None:
        if self.scene3d is not None:
            t0, c0 = time.perf_counter(), time.process_time()
            self.scene3d.update(self.state.design)
            self.timings_s["scene_s"] = time.perf_counter() - t0
            self.timings_s["scene_cpu_s"] = time.process_time() - c0

    def refresh(self) -> None:
        """The check, then the scene."""
        self.refresh_check()
        self.refresh_scene()

    def after_edit(self, refresh: bool = True) -> None:
        if self.autosave_later:
            self._autosave_due = True
        else:
            self.document.autosave(self.state.design)
        self.order = None
        if refresh:
            self.refresh_check()

    def write_autosave(self) -> None:
        """Write the autosave sidecar an edit left due (``autosave_later``)."""
        if self._autosave_due:
            self._autosave_due = False
            self.document.autosave(self.state.design)

    def selected_readout(self):
        p = self.state.selected_patch()
        return None if p is None else readout(self.dmap, p.diameter_mm, p.fill)

    def drag_to(self, dx_mm: float, dy_mm: float) -> None:
        """The dragged patches follow the pointer, (dx, dy) mm from the press: the canvas draws
        them there with their edge rule; the design changes on release (``move`` /
        ``move_selection``)."""
        self.drag_offset = (float(dx_mm), float(dy_mm)) if self.dragging else None

    def end_drag(self) -> None:
        self.dragging, self.drag_offset = (), None

    def _canvas_args(self) -> tuple:
        hoops = fabrication.hooping_outlines(self.order, self.eta) if self.order is not None else ()
        design = self.state.design
        if self.dragging and self.drag_offset is not None:
            design = self.state.moved(self.dragging, *self.drag_offset)
        return (design, heights_mm(self.dmap, design), self.eta, self.state.selected,
                live_check.patch_status(self.violations), hoops, self.view(),
                self.state.also_selected, self.dragging, self.checker.limits)

    def canvas_svg(self) -> str:
        return canvas.svg(*self._canvas_args())

    def canvas_layers(self) -> tuple[str, str, str]:
        """The canvas as (pieces, patches, rulers) SVGs, ``canvas.layers``."""
        return canvas.layers(*self._canvas_args())

    def canvas_patches(self) -> str:
        """The patches' layer alone (``canvas.patches_svg``): what a drag changes."""
        return canvas.patches_svg(*self._canvas_args())

    def view(self):
        return self.view_box or canvas.view_of(self.state.design)

    # --- the canvas's view --------------------------------------------------------------
    def zoom(self, factor: float, about_mm=None) -> None:
        """Zoom by ``factor`` (> 1 in) about a garment point (default: the view's centre)."""
        v = self.view()
        about = about_mm if about_mm is not None else (v.x0 + v.width / 2, -(v.y0 + v.height / 2))
        self.view_box = canvas.zoomed(v, factor, about, canvas.view_of(self.state.design))

    def pan(self, dx_mm: float, dy_mm: float) -> None:
        self.view_box = canvas.panned(self.view(), dx_mm, dy_mm)

    def fit_view(self) -> None:
        self.view_box = None

    @property
    def sizes(self) -> list[str]:
        """The sizes of the pattern (empty without one)."""
        return [] if self.pattern is None else list(dict.fromkeys(p.size for p in self.pattern))

    @property
    def size(self) -> str | None:
        """The size of the design's pieces."""
        return self.state.design.pieces[0].size if self.state.design.pieces else None

    # --- actions ------------------------------------------------------------------------
    def set_size(self, size: str) -> None:
        """Put the design on another size of its pattern (``select_pieces``, as ``import
        --size`` does), one undo step; the view fits the new pieces."""
        if self.pattern is None:
            raise InvalidInputError("the design was not started from a graded pattern")
        names = [p.name for p in self.state.design.pieces]
        source = self.state.design.pieces[0].source if self.state.design.pieces else None
        self.state.set_pieces(select_pieces(self.pattern, size, names, source))
        self.view_box = None
        self.after_edit()

    def add(self, centre_mm) -> str:
        pid = self.state.add_patch(centre_mm)
        self.after_edit()
        return pid

    def move(self, patch_id, centre_mm) -> None:
        self.state.move_patch(patch_id, centre_mm)
        self.after_edit()

    def edit(self, patch_id, refresh: bool = True, **changes) -> None:
        """Edit a patch; ``refresh`` False leaves the check to a later ``refresh_check()``
        (the page shows the readout first)."""
        self.state.edit_patch(patch_id, **changes)
        self.after_edit(refresh)

    def remove(self, patch_id) -> None:
        self.state.remove_patch(patch_id)
        self.after_edit()

    def remove_selection(self) -> None:
        self.state.remove_patches(self.state.selection)
        self.after_edit()

    def move_selection(self, dx_mm: float, dy_mm: float) -> None:
        self.state.move_patches(self.state.selection, dx_mm, dy_mm)
        self.after_edit()

    def set_composite(self, core_diameter_mm: float | None, core_fill: float | None = None) -> None:
        """Give the selected patch a composite core (None: none), one undo step."""
        core = None if core_diameter_mm is None else CompositeSpec(float(core_diameter_mm),
                                                                   float(core_fill))
        self.state.edit_patch(self._selected_id(), own_step=True, composite=core)
        self.after_edit()

    def set_conductive(self, selection: str | None) -> None:
        """Set the selected patch's conductive triangles (``ring:0``, ...; None or "": none)."""
        self.state.edit_patch(self._selected_id(), own_step=True,
                              conductive=(selection or "").strip() or None)
        self.after_edit()

    def _selected_id(self) -> str:
        if self.state.selected is None:
            raise InvalidInputError("select a patch first")
        return self.state.selected

    def undo(self) -> None:
        self.state.undo()
        self.after_edit()

    def redo(self) -> None:
        self.state.redo()
        self.after_edit()

    def run_inverse(self, target: InverseTarget) -> list:
        self.candidates = inverse_panel.candidates(target, self.dmap, self.state)
        return self.candidates

    def apply_candidate(self, index: int, centre_mm=None) -> str:
        """Give the selected patch candidate ``index``'s design, or with ``centre_mm`` place a
        new patch with it there (one undo step either way)."""
        if not 0 <= index < len(self.candidates):
            raise InvalidInputError(f"candidate {index + 1}: there are {len(self.candidates)}")
        pid = inverse_panel.apply(self.state, self.candidates[index].candidate, centre_mm)
        self.after_edit()
        return pid

    def save(self) -> str:
        self.document.save(self.state.design)
        return self.document.path

    def group(self, mode: str = "garment") -> None:
        _, self.order = fabrication.hoopings(self.state.design, FabricateOptions(mode=mode))
        self.order_mode = mode

    def plan_preview(self, k: int) -> tuple[str, dict]:
        """(SVG, counts) of the stitch plan of hooping ``k`` (0-based) of the last grouping."""
        if self.order is None:
            raise InvalidInputError("group the design into hoopings first")
        if not 0 <= k < len(self.order.hoopings):
            raise InvalidInputError(f"hooping {k + 1}: there are {len(self.order.hoopings)}")
        plan = fabrication.hooping_plan(self.state.design, self.order, k,
                                        FabricateOptions(mode=self.order_mode))
        h = self.order.hoopings[k]
        return (stitch_preview.plan_svg(plan.plan, h, f"hooping {k + 1}: {h.hoop.name}"),
                stitch_preview.counts(plan.plan))

    def export(self, outdir, mode: str = "garment", force: bool = False):
        saved = not self.document.dirty(self.state.design)
        self.exported = fabrication.export(self.state.design, outdir,
                                           FabricateOptions(mode=mode, force=force), saved)
        return self.exported

    def exported_file(self, name: str) -> bytes:
        """The bytes of file ``name`` of the last export (only its files can be read)."""
        if self.exported is None or name not in self.exported.files:
            raise InvalidInputError(f"{name!r} is not a file of the last export")
        with open(os.path.join(self.exported.outdir, name), "rb") as f:
            return f.read()
