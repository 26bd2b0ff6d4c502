"""The studio's web page (trame, Vue 3 with Vuetify 3, VTK local or remote view): binds the widgets to a
``Session`` and serves it.

Design Mode: the canvas (SVG from ``canvas``; a press on a patch selects it, Shift+press adds
it to the selection or takes it out, and dragging it moves the selection: the patches follow
the pointer with their piece-edge rule (throttled moves, ``DRAG_THROTTLE_MS``) and the design
changes on release; a click on an empty spot of a piece adds a
patch, a drag from an empty spot pans, the wheel and the toolbar's - / Fit / + zoom; Delete
removes the selection), the inspector (diameter and fill sliders, state, the live readout,
the composite core and the conductive triangles), the 3D view (the scene of ``scene3d``,
drawn by the browser's WebGL or rendered on the server: ``render_mode``), the
inverse-design panel (apply a candidate to the selected patch, or place it where the next
click lands) and the constraint panel. Fabrication Mode:
hoop grouping drawn on the canvas, each hooping's stitch plan (a click on it), export of the
fabrication folder and a download link for each exported file.
"""
from __future__ import annotations

import asyncio
import functools
import os
import time

from stitchswitch.errors import InvalidInputError, StitchSwitchError
from stitchswitch.preview3d import colours
from stitchswitch.reduced.design_space.inverse import InverseTarget
from stitchswitch.studio import canvas, heap, live_check
from stitchswitch.studio.check_timer import CheckTimer
from stitchswitch.studio.readout import profile_svg
from stitchswitch.studio.view3d import render_mode
from stitchswitch.studio.view3d.camera_fit import CameraFit
from stitchswitch.studio.view3d.image_channel import ImageChannel
from stitchswitch.studio.view3d.scene3d import PlotterSync
from stitchswitch.studio.view3d.view_channel import ViewChannel

#: the pointer expression passed to the canvas handlers: position on the SVG and its size, px,
#: then the Shift key
POINTER = ("[$event.clientX - $event.currentTarget.getBoundingClientRect().left, "
           "$event.clientY - $event.currentTarget.getBoundingClientRect().top, "
           "$event.currentTarget.clientWidth, $event.currentTarget.clientHeight, $event.shiftKey]")
WHEEL = POINTER[:-len(", $event.shiftKey]")] + ", $event.deltaY]"
#: while the button is down, the pointer's latest position goes to the server at most this
#: often (ms; the last one always goes): the dragged patches follow it on the canvas
DRAG_THROTTLE_MS = 40
DRAG = (f"if ($event.buttons === 1) {{ window.studioDragAt = {POINTER}; "
        "if (!window.studioDragTimer) window.studioDragTimer = window.setTimeout(() => { "
        "window.studioDragTimer = null; trigger('studio_drag', window.studioDragAt) }, "
        f"{DRAG_THROTTLE_MS}) }}")
#: each canvas layer fills the canvas, stacked in the order made
CANVAS_LAYER = "position:absolute; inset:0"
#: zoom factor per wheel step or button press
ZOOM_STEP = 1.25
#: the 3D scene is built once the page has drawn the panel (it says so in the next animation
#: frame after the edit counter changed), at the latest this long after the panel: the scene's
#: build and serialization would hold the server's event loop before the panel's message is
#: written, and the browser's WebGL render of the scene would hold the frame that shows it
SCENE_DELAY_S = 0.15
#: a server-rendered frame waits this long after the panel's message: writing it to the
#: websocket takes the event loop a few turns, and a render started before that holds it (a
#: readout sent so was shown 66-69 ms after a slider step instead of 42-47, median)
PANEL_WRITE_S = 0.005
#: the page's acknowledgement that it has drawn the panel of an edit
PANEL_SHOWN = "window.requestAnimationFrame(() => trigger('studio_panel_shown'))"
#: the page's word that an image of the server-rendered view has loaded (the ``load`` of the
#: view's ``img``, caught on its way down to it), in the frame that draws it (``CheckTimer``)
VIEW_SHOWN = "window.requestAnimationFrame(() => trigger('studio_view_shown'))"
#: run by the page before the 3D view makes its WebGL context: on a software WebGL renderer
#: (no GPU: SwiftShader, llvmpipe) the view's context is made without multisampling. vtk.js
#: asks for the browser's default, antialiased (4x multisampled) drawing buffer, and a
#: software renderer rasterizes and resolves every sample: it made the frame of the
#: 40-patch scene take 215 instead of 48 ms (docs/studio.md, "Speed"). With a GPU the
#: default stays.
SOFTWARE_GL_NO_MSAA = r"""(() => {
  const probe = document.createElement('canvas').getContext('webgl2');
  if (!probe) return;
  const info = probe.getExtension('WEBGL_debug_renderer_info');
  const name = String(probe.getParameter(info ? info.UNMASKED_RENDERER_WEBGL : probe.RENDERER));
  const lose = probe.getExtension('WEBGL_lose_context');
  if (lose) lose.loseContext();
  if (!/%s/i.test(name)) return;
  const getContext = HTMLCanvasElement.prototype.getContext;
  HTMLCanvasElement.prototype.getContext = function (type, attrs) {
    if (type === 'webgl2' || type === 'webgl') attrs = Object.assign({}, attrs, {antialias: false});
    return getContext.call(this, type, attrs);
  };
  window.studioSoftwareGL = name;
})();""" % render_mode.SOFTWARE_RENDERER
#: the inspector's sliders follow their value at once: Vuetify eases the thumb and the track
#: over 0.3 s after each step, and every eased frame is rasterized and composited again, on
#: the CPU without a GPU, beside the server (the page's main-thread time per slider step:
#: docs/studio.md, "Speed")
SLIDER_NO_EASING = "#slider-d *, #slider-fill * { transition: none !important; }"
#: the page's note that a call to the server is under way (trame's ``trame__busy``), in its
#: bottom-left corner, shown only once the call has lasted this long (s): a CSS animation's
#: delay, which draws no frames meanwhile. It stands in for trame's layout footer, whose
#: progress circle spun whenever a call was in flight: on every slider step the page
#: re-rendered and rasterized its animation for a few hundred milliseconds, on the CPU without
#: a GPU, beside the step's image (docs/studio.md, "Speed")
BUSY_AFTER_S = 0.4
BUSY_STYLE = (".studio-busy { visibility: hidden; position: fixed; left: 8px; bottom: 6px; "
              "z-index: 2000; padding: 0 6px; background: white; border: 1px solid #ccc; } "
              ".studio-busy--on { animation: studio-busy-show 0s linear %gs forwards; } "
              "@keyframes studio-busy-show { to { visibility: visible; } }" % BUSY_AFTER_S)
#: the server-rendered view's images: JPEG quality at rest and while rotating or zooming (and
#: of a dragged slider's drafts, ``ImageChannel``), and full size while rotating (a software
#: frame of the scene alone takes 13 ms)
REMOTE_VIEW_QUALITY = {"still_quality": 90, "interactive_quality": 70, "interactive_ratio": 1}
#: the state key of the page's size of the WebGL view (``client.SizeObserver``: its size, CSS
#: px, and the pixel ratio)
VIEW_SIZE = "view3d_size"
#: the WebGL view's interactor events that end a rotation, pan or zoom by the user
USER_CAMERA_EVENTS = ["EndAnimation", "EndMouseWheel"]
#: the 3D view's name on the page (its full scene state is the state key ``scene_`` + it)
VIEW_REF = "studio_view"
READOUT_KEYS = (("h", "h_mm"), ("r_a", "r_a_mm"), ("z_a", "z_a_mm"), ("r_b", "r_b_mm"),
                ("z_b", "z_b_mm"))


def _plotter():
    import pyvista as pv
    from vtkmodules.vtkCommonCore import vtkLogger

    pv.OFF_SCREEN = True
    if not os.environ.get("DISPLAY"):     # VTK falls back to offscreen; its X warning is noise
        vtkLogger.SetStderrVerbosity(vtkLogger.VERBOSITY_ERROR)
    pl = pv.Plotter(off_screen=True, window_size=(600, 450))
    pl.set_background("white")
    return pl


def build_app(session, server=None, view_mode: str = "auto"):
    """The trame server with the studio page for ``session``; its 3D view drawn where
    ``render_mode.choose(view_mode)`` says."""
    from trame.app import get_server
    from trame.ui.vuetify3 import SinglePageWithDrawerLayout
    from trame.widgets import client, html
    from trame.widgets import vtk as vtk_widgets
    from trame.widgets import vuetify3 as v3

    server = server or get_server("stitchswitch-studio", client_type="vue3")
    state, ctrl = server.state, server.controller
    pl = _plotter()
    renderer_name = functools.cache(lambda: render_mode.server_renderer(type(pl.ren_win)))
    state.view_mode = render_mode.choose(view_mode, renderer_name)
    if state.view_mode == "server" and render_mode.is_software(renderer_name()):
        # single-sampled: a software rasterizer spends 3x the frame on 8 samples (42 ms
        # against 13 ms for the 40-patch scene)
        pl.ren_win.SetMultiSamples(0)
        # three lights instead of pyvista's light kit of five, for the same look: a software
        # rasterizer lights every pixel once per light (the 40-patch frame: 15-20 against
        # 10-14 ms)
        pl.enable_3_lights()
    view_sync = PlotterSync(pl)
    session.autosave_later = True
    drag = {"id": None, "start": None}
    pending = {"scene": None}
    camera = CameraFit(pl)
    page_camera = {"fit": None}       # the fit the WebGL view's camera was last given
    sync_counts: dict = {}
    shown_last = [None, None]         # the design and check verdicts the 3D view was sent

    def push_readout() -> None:
        r = session.selected_readout()
        state.profile_svg = "" if r is None else profile_svg(r.r_mm, r.z_mm)
        state.readout = ({} if r is None else
                         {k: (None if r.keypoints_mm[key] is None else round(r.keypoints_mm[key], 2))
                          for k, key in READOUT_KEYS}
                         | {"force": None if r.force_N is None else round(r.force_N, 3),
                            "message": r.message})

    def push_panel() -> None:
        """Everything but the 3D view, sent at once; the scene follows (``schedule_scene``)."""
        s = session.state
        p = s.selected_patch()
        with state:
            push_readout()
            state.selected = s.selected
            state.selection = list(s.selection)
            state.size = session.size
            if p is not None:
                state.diameter, state.fill, state.patch_state = p.diameter_mm, p.fill, p.state
                state.composite_on = p.composite is not None
                if p.composite is not None:
                    state.core_d, state.core_fill = p.composite.core_diameter_mm, p.composite.core_fill
                state.conductive = p.conductive or ""
            state.canvas_pieces, state.canvas_svg, state.canvas_rulers = session.canvas_layers()
            state.violations = live_check.rows(session.violations)
            state.small_pieces = live_check.small_rows(session.small_pieces)
            state.n_errors = live_check.errors(session.violations)
            state.can_undo, state.can_redo = s.can_undo, s.can_redo
            state.dirty = session.document.dirty(s.design)
            state.n_patches = len(s.design.patches)
            state.edits = s.changed
        state.flush()
        session.write_autosave()

    def build_view() -> None:
        """The scene and the view's actors, for the view's channel's ``send``."""
        shown_last[:] = (session.state.design, colours.status_from_violations(session.violations))
        session.refresh_scene()
        t0, c0 = time.perf_counter(), time.process_time()
        sync_counts.clear()
        sync_counts.update(view_sync.sync(session.scene3d, session.violations))
        if not camera.fitted:
            camera.fit()
        session.timings_s["sync_s"] = time.perf_counter() - t0
        session.timings_s["sync_cpu_s"] = time.process_time() - c0

    def scene_sent(send_s: float, send_cpu_s: float) -> None:
        """After the view's delta or image, on the same websocket: the timings and the scene
        stamp."""
        sent = {"view_send_s": send_s, "view_send_cpu_s": send_cpu_s}
        state.timings = ({k: round(1000 * v, 2) for k, v in (session.timings_s | sent).items()}
                         | sync_counts)
        state.scene_stamp = session.state.changed
        state.flush()

    def push_scene() -> None:
        pending["scene"] = None
        channel.send()

    def schedule_scene() -> None:
        """The 3D view after the panel (rendered on the server: after a slider step's readout)
        has gone out, when the design or the check's verdicts changed (a selection alone
        changes nothing there); edits arriving meanwhile join it."""
        shown = (session.state.design, colours.status_from_violations(session.violations))
        if shown[0] is shown_last[0] and shown[1] == shown_last[1]:
            return
        if pending["scene"] is None:
            # a server-rendered frame does not hold the page's frame: it follows the panel
            delay = PANEL_WRITE_S if state.view_mode == "server" else SCENE_DELAY_S
            pending["scene"] = asyncio.get_event_loop().call_later(delay, push_scene)

    @ctrl.trigger("studio_panel_shown")
    def panel_shown():
        """The page has drawn the panel of the latest edit: the 3D view's turn."""
        if pending["scene"] is not None:
            pending["scene"].cancel()
            push_scene()

    def push() -> None:
        push_panel()
        schedule_scene()

    def guarded(fn):
        def run(*args, **kwargs):
            try:
                fn(*args, **kwargs)
                state.message = ""
            except (InvalidInputError, StitchSwitchError, OSError) as exc:
                state.message = f"Error: {exc}"
            push()
        return run

    @guarded
    def on_down(px, py, w, h, shift=False):
        """A press: on a patch, select it (Shift: add it to the selection or take it out) and
        draw the edge rule of the patches about to be dragged; elsewhere, start a pan or an add."""
        pt = canvas.to_mm(session.view(), px, py, w, h)
        pid = session.state.patch_at(pt)
        drag["id"], drag["start"] = pid, pt
        if pid is not None and shift:
            session.state.toggle_select(pid)
        elif pid is not None and pid not in session.state.selection:
            session.state.select(pid)
        session.dragging = session.state.selection if pid in session.state.selection else ()

    @guarded
    def on_up(px, py, w, h, shift=False):
        """A release: after a press on a selected patch, move the selection; after a press on
        an empty spot, pan the view (moved) or add a patch there (not moved)."""
        pt = canvas.to_mm(session.view(), px, py, w, h)
        pid, start = drag["id"], drag["start"]
        drag["id"] = drag["start"] = None
        session.end_drag()
        if start is None:
            return
        dx, dy = pt[0] - start[0], pt[1] - start[1]
        moved = abs(dx) + abs(dy) > 1.0
        if pid is not None and moved and pid in session.state.selection:
            if len(session.state.selection) > 1:
                session.move_selection(dx, dy)
            else:
                p = session.state.design.patch(pid)
                session.move(pid, (p.centre_mm[0] + dx, p.centre_mm[1] + dy))
        elif pid is None and moved:
            session.pan(dx, dy)
        elif pid is None and not shift and state.placing is not None:
            k, state.placing = state.placing, None
            session.apply_candidate(k, pt)
        elif pid is None and not shift:
            session.add(pt)

    @ctrl.trigger("studio_drag")
    def on_drag(px, py, w, h, shift=False):
        """A move with the button down after a press on a selected patch: the canvas draws the
        dragged patches and their edge rule where the pointer is (the design changes on release)."""
        if drag["start"] is None or not session.dragging:
            return
        pt = canvas.to_mm(session.view(), px, py, w, h)
        session.drag_to(pt[0] - drag["start"][0], pt[1] - drag["start"][1])
        state.canvas_svg = session.canvas_patches()
        state.drag_stamp += 1
        state.flush()

    @guarded
    def on_wheel(px, py, w, h, delta):
        pt = canvas.to_mm(session.view(), px, py, w, h)
        session.zoom(ZOOM_STEP if float(delta) < 0 else 1.0 / ZOOM_STEP, pt)

    @state.change("size")
    def on_size(size, **_):
        if size and session.sizes and size != session.size:
            guarded(session.set_size)(size)

    @state.change("diameter", "fill", "patch_state")
    def on_slider(diameter, fill, patch_state, **_):
        p = session.state.selected_patch()
        if p is None or (p.diameter_mm, p.fill, p.state) == (float(diameter), float(fill), patch_state):
            return
        try:            # the readout (the map answers at once), then the 3D view and the check
            session.edit(p.id, refresh=False, diameter_mm=float(diameter), fill=float(fill),
                         state=patch_state)
            push_readout()
            state.readout_stamp = session.state.changed
        except (InvalidInputError, StitchSwitchError, OSError) as exc:
            state.message = f"Error: {exc}"
            checks.soon()
            return
        if state.view_mode == "server":
            # rendered on the server, the frame is rendered at once and its message carries the
            # readout: a frame rendered after the readout's message shared the two cores with
            # the page drawing the readout, and came 15 ms later (docs/studio.md, "Speed"). Its
            # outlines are those of the last check (a check that changes their verdicts has the
            # frame rendered again); the check waits until the page draws the frame's image
            # (``CheckTimer``). The frame is a draft, a quarter of the pixels, until the
            # slider rests (``ImageChannel``)
            if pending["scene"] is not None:
                pending["scene"].cancel()
                pending["scene"] = None
            checks.after_image()
            channel.send(draft=True)
            state.flush()
            return
        state.flush()
        checks.soon()

    def check_now():
        session.refresh_check()
        push()

    checks = CheckTimer(check_now)
    ctrl.trigger("studio_view_shown")(checks.view_shown)

    def on_inverse():
        try:
            r_a = float(state.target_ra) if state.target_ra not in (None, "") else None
            d_max = float(state.target_dmax) if state.target_dmax not in (None, "") else None
            p_min = float(state.target_pmin) if state.target_pmin not in (None, "") else None
            target = InverseTarget(height_mm=float(state.target_h), radius_mm=r_a,
                                   max_diameter_mm=d_max, min_fill=p_min, count=3)
            state.candidates = [c.as_dict() | {"index": k}
                                for k, c in enumerate(session.run_inverse(target))]
            state.message = "" if state.candidates else "no candidate meets the target"
        except (InvalidInputError, ValueError) as exc:
            state.candidates, state.message = [], f"Error: {exc}"

    def on_group():
        guarded(session.group)(state.fab_mode)
        state.plan_k, state.plan_svg = 0, ""
        if session.order is not None:
            state.hoopings = [{"k": k, "hoop": h.hoop.name, "patches": ", ".join(h.patch_ids)}
                              for k, h in enumerate(session.order.hoopings, start=1)]

    def on_plan(k):
        try:
            state.plan_svg, state.plan_counts = session.plan_preview(int(k) - 1)
            state.plan_k = int(k)
        except (InvalidInputError, StitchSwitchError) as exc:
            state.message = f"Error: {exc}"

    @ctrl.trigger("studio_scene_loaded")
    def scene_loaded():
        """The page has loaded the scene in flight (vtk.js's afterSceneLoaded)."""
        channel.loaded()
        if page_camera["fit"] != camera.fits:
            push_page_camera()

    def fit_3d() -> None:
        """The "Fit 3D" button: the camera back on the whole design."""
        camera.fit()
        if state.view_mode == "server":
            channel.send()
        else:
            push_page_camera()

    def push_page_camera() -> None:
        """The camera's latest fit to the page's WebGL view, which takes the server's camera
        from the first scene only (vtk.js's synchronizer sets a camera once)."""
        if camera.fitted and not camera.released and page_camera["fit"] != camera.fits:
            page_camera["fit"] = camera.fits
            server.js_call(VIEW_REF, "setCamera", camera.pose())

    @ctrl.trigger("studio_file")
    def exported_file(name):
        """The bytes of an exported file, for the page's download links."""
        return session.exported_file(name)

    def on_export():
        try:
            result = session.export(os.path.expanduser(state.export_dir), state.fab_mode)
            state.exported = list(result.files)
            state.message = f"exported {len(result.files)} files to {result.outdir}"
        except (InvalidInputError, StitchSwitchError, OSError) as exc:
            state.message = f"Error: {exc}"

    def on_save():
        guarded(session.save)()
        if not state.message:
            state.message = f"saved {session.document.path}"

    def on_apply(index):
        guarded(session.apply_candidate)(int(index))

    def on_place(index):
        """Arm placing: the next click on an empty spot of a piece adds the candidate there."""
        state.placing = int(index)
        state.message = "click on a piece to place the candidate (Esc cancels)"

    def on_key(key):
        if key in ("Delete", "Backspace") and session.state.selected is not None:
            on_delete()
        elif key == "Escape" and state.placing is not None:
            state.placing, state.message = None, ""

    def on_delete():
        guarded(session.remove_selection)()

    def on_composite():
        core = state.core_d if state.composite_on else None
        guarded(session.set_composite)(None if core in (None, "") else float(core),
                                       None if core in (None, "") else float(state.core_fill))

    def on_conductive():
        guarded(session.set_conductive)(state.conductive)

    def on_violation(index):
        v = session.violations[index]
        if v.patches:
            guarded(session.state.select)(v.patches[0])

    state.update({"message": "", "candidates": [], "hoopings": [], "exported": [], "mode": "design",
                  "fab_mode": "garment", "export_dir": os.path.join(
                      os.path.dirname(os.path.abspath(session.document.path)), "fabrication"),
                  "target_h": 15.0, "target_ra": "", "target_dmax": "", "target_pmin": "",
                  "diameter": 60.0, "fill": 0.5, "patch_state": "up", "readout_stamp": 0,
                  "selection": [], "composite_on": False, "core_d": 20.0, "core_fill": 0.9,
                  "conductive": "", "sizes": session.sizes, "size": session.size,
                  "small_pieces": [], "plan_k": 0, "plan_svg": "", "plan_counts": {}, "placing": None, "scene_stamp": 0,
                  "drag_stamp": 0,
                  "timings": {}})

    with SinglePageWithDrawerLayout(server, full_height=True) as layout:
        layout.title.set_text("stitchswitch studio")
        layout.footer.clear()       # its progress circle: ``BUSY_STYLE``
        layout.footer.hide()
        client.Style(SLIDER_NO_EASING + " " + BUSY_STYLE)
        with layout.toolbar:
            v3.VSpacer()
            with v3.VBtnToggle(v_model=("mode",), mandatory=True, density="compact"):
                v3.VBtn("Design", value="design", id="mode-design")
                v3.VBtn("Fabrication", value="fabrication", id="mode-fabrication")
            v3.VBtn("Undo", click=guarded(session.undo), disabled=("!can_undo",), id="undo")
            v3.VBtn("Redo", click=guarded(session.redo), disabled=("!can_redo",), id="redo")
            v3.VBtn("Save", click=on_save, id="save")
            with html.Div(v_if="sizes.length > 1", id="size-picker", style="width:110px"):
                v3.VSelect(v_model=("size",), items=("sizes",), label="size", density="compact",
                           hide_details=True)
            v3.VBtn("-", click=guarded(lambda: session.zoom(1.0 / ZOOM_STEP)), id="zoom-out",
                    size="small")
            v3.VBtn("Fit", click=guarded(session.fit_view), id="fit-view", size="small")
            v3.VBtn("+", click=guarded(lambda: session.zoom(ZOOM_STEP)), id="zoom-in", size="small")
            html.Span("{{ dirty ? 'unsaved changes' : 'saved' }}", classes="text-caption mx-2",
                      id="dirty")
            v3.VBtn("Fit 3D", click=fit_3d, id="fit-3d", size="small")
            html.Span("3D view: {{ view_mode == 'server' ? 'rendered on the server' : "
                      "'WebGL in the browser' }}", classes="text-caption mx-2", id="view-mode")
            html.Span("{{ view_mode }}", id="view-mode-key", style="display:none")
            html.Span("{{ edits }}", id="edits", style="display:none")
            client.ClientStateChange(value="edits", change=PANEL_SHOWN)
            html.Span("{{ scene_stamp }}", id="scene-stamp", style="display:none")
            html.Span("{{ readout_stamp }}", id="readout-stamp", style="display:none")
            html.Span("{{ drag_stamp }}", id="drag-stamp", style="display:none")
            html.Span("{{ JSON.stringify(timings) }}", id="timings", style="display:none")
        with layout.drawer as drawer:
            drawer.width = 380
            with html.Div(v_if="mode == 'design'", classes="pa-2"):
                html.H4("Patch {{ selected || '(none: click a piece to add one)' }}", id="inspector-title")
                html.Div("{{ selection.length }} selected (Shift+click adds or removes; drag moves "
                         "them all, Delete removes them all)", v_if="selection.length > 1",
                         id="multi", classes="text-caption")
                with html.Div(v_if="selected"):
                    with html.Div(id="slider-d"):
                        v3.VSlider(v_model=("diameter",), label="d (mm)", min=20, max=150, step=0.5,
                                   thumb_label=True, hide_details=True)
                    with html.Div(id="slider-fill"):
                        v3.VSlider(v_model=("fill",), label="fill", min=0.05, max=1.0, step=0.005,
                                   thumb_label=True, hide_details=True)
                    v3.VSelect(v_model=("patch_state",), items=("['up', 'down']",), label="state",
                               density="compact", hide_details=True)
                    html.Div("h {{ readout.h }} mm | r_a {{ readout.r_a }} | z_a {{ readout.z_a }} | "
                             "r_b {{ readout.r_b }} | z_b {{ readout.z_b }} mm | force "
                             "{{ readout.force }} N {{ readout.message }}", id="readout",
                             classes="text-body-2 my-1")
                    html.Div(v_html=("profile_svg",), id="profile")
                    with html.Div(classes="d-flex align-center", id="composite"):
                        v3.VCheckbox(v_model=("composite_on",), label="composite core",
                                     density="compact", hide_details=True, id="composite-on")
                        v3.VTextField(v_model=("core_d",), label="core d (mm)", density="compact",
                                      hide_details=True, disabled=("!composite_on",), id="core-d")
                        v3.VTextField(v_model=("core_fill",), label="core fill", density="compact",
                                      hide_details=True, disabled=("!composite_on",), id="core-fill")
                        v3.VBtn("Set", click=on_composite, size="x-small", id="set-composite")
                    with html.Div(classes="d-flex align-center", id="conductive"):
                        v3.VTextField(v_model=("conductive",), label="conductive (ring:0, index:..., "
                                      "annulus:IN:OUT)", density="compact", hide_details=True,
                                      id="conductive-text")
                        v3.VBtn("Set", click=on_conductive, size="x-small", id="set-conductive")
                    v3.VBtn("Delete patch", click=on_delete,
                            size="small", id="delete")
                v3.VDivider(classes="my-2")
                html.H4("Inverse design")
                with html.Div(id="target-h"):
                    v3.VTextField(v_model=("target_h",), label="target h (mm)", density="compact",
                                  hide_details=True)
                v3.VTextField(v_model=("target_ra",), label="target r_a (mm, optional)",
                              density="compact", hide_details=True)
                v3.VTextField(v_model=("target_dmax",), label="max d (mm, optional)",
                              density="compact", hide_details=True)
                v3.VTextField(v_model=("target_pmin",), label="min fill (optional)",
                              density="compact", hide_details=True)
                v3.VBtn("Run inverse design", click=on_inverse, size="small", id="run-inverse")
                with html.Div(v_for="c in candidates", key="c.index", classes="text-body-2"):
                    html.Span("d {{ c.d_mm }} mm, fill {{ c.fill }}: h {{ c.h_mm }}, r_a {{ c.r_a_mm }},"
                              " F {{ c.force_N }} N, {{ c.feasible ? 'passes the check' : "
                              "c.check_errors + ' check errors' }} ")
                    v3.VBtn("Apply", size="x-small", click=(on_apply, "[c.index]"),
                            classes="apply-candidate")
                    v3.VBtn("Place", size="x-small", click=(on_place, "[c.index]"),
                            classes="place-candidate")
                v3.VDivider(classes="my-2")
                html.H4("Constraints: {{ n_errors }} error(s)", id="check-title")
                with html.Div(v_for="v in violations", key="v.index", classes="text-body-2 violation",
                              click=(on_violation, "[v.index]"), style="cursor:pointer"):
                    html.Span("{{ v.severity }} {{ v.rule }}: {{ v.message }}")
                html.Div("{{ w }}", v_for="w in small_pieces", key="w",
                         classes="text-body-2 small-pieces")
            with html.Div(v_if="mode == 'fabrication'", classes="pa-2"):
                v3.VSelect(v_model=("fab_mode",), items=("['garment', 'free']",), label="grouping",
                           density="compact")
                v3.VBtn("Group into hoopings", click=on_group, size="small", id="group")
                with html.Div(v_for="h in hoopings", key="h.k", classes="text-body-2 hooping",
                              click=(on_plan, "[h.k]"), style="cursor:pointer"):
                    html.Span("{{ h.k }}. {{ h.hoop }}: {{ h.patches }} (stitch plan)")
                with html.Div(v_if="plan_k", id="plan"):
                    html.Div("Hooping {{ plan_k }}: {{ plan_counts.stitches }} stitches, "
                             "{{ plan_counts.jumps }} jumps, {{ plan_counts.trims }} trims, "
                             "{{ plan_counts.colour_changes }} colour changes, about "
                             "{{ plan_counts.minutes }} min", classes="text-caption", id="plan-counts")
                    html.Div(v_html=("plan_svg",), id="plan-svg")
                with html.Div(id="export-dir"):
                    v3.VTextField(v_model=("export_dir",), label="export folder", density="compact")
                v3.VBtn("Export", click=on_export, size="small", id="export")
                with html.Div(v_for="f in exported", key="f", classes="text-caption exported"):
                    html.A("{{ f }}", href="#", classes="download",
                           click="utils.download(f, trigger('studio_file', [f])); $event.preventDefault()")
            html.Div("{{ message }}", id="message", classes="text-body-2 pa-2 text-red")
        with layout.content:
            html.Span("working...", id="busy", classes=(
                "{'studio-busy': true, 'studio-busy--on': trame__busy, 'text-caption': true}",))
            with html.Div(style="display:flex; height:100%; width:100%"):
                # the canvas's three layers (``canvas.layers``) one over the other: an edit
                # replaces only the patches' SVG
                with html.Div(id="canvas", style="flex:1; min-width:0; user-select:none; "
                              "position:relative", mousedown=(on_down, POINTER),
                              mouseup=(on_up, POINTER), tabindex="0", mousemove=DRAG,
                              wheel=(on_wheel, WHEEL), keydown=(on_key, "[$event.key]")):
                    for key in ("canvas_pieces", "canvas_svg", "canvas_rulers"):
                        html.Div(v_html=(key,), style=CANVAS_LAYER)
                if state.view_mode == "browser":
                    client.Script(SOFTWARE_GL_NO_MSAA)      # before the view makes its context
                with html.Div(style="flex:1; min-width:0", id="view3d",
                              __events=[("image_loaded", "load.capture")],
                              image_loaded=VIEW_SHOWN if state.view_mode == "server" else None):
                    if state.view_mode == "server":
                        view = vtk_widgets.VtkRemoteView(pl.ren_win, ref=VIEW_REF,
                                                         **REMOTE_VIEW_QUALITY)
                        channel = ImageChannel(
                            server, view, pl.ren_win, build_view, scene_sent,
                            checks.image_published,
                            still_quality=REMOTE_VIEW_QUALITY["still_quality"],
                            draft_quality=REMOTE_VIEW_QUALITY["interactive_quality"])
                    else:
                        # the scene's synchronizations in the browser (afterSceneLoaded: vtk.js
                        # has the new geometry, its arrays fetched), counted for the benchmark
                        # and tests
                        # the page's size of the view (the fit is made for it) and the end of
                        # the user's rotations and zooms (no fit after them): ``CameraFit``
                        with client.SizeObserver(VIEW_SIZE):
                            view = vtk_widgets.VtkLocalView(
                                pl.ren_win, ref=VIEW_REF,
                                interactor_events=("events", USER_CAMERA_EVENTS),
                                **{event: camera.release for event in USER_CAMERA_EVENTS},
                                before_scene_loaded="window.studioSceneBusy = true",
                                after_scene_loaded="window.studioSceneBusy = false; "
                                                   "window.studioSceneLoads = (window."
                                                   "studioSceneLoads || 0) + 1; "
                                                   "trigger('studio_scene_loaded')")
                        channel = ViewChannel(server, view, pl.ren_win, VIEW_REF, build_view,
                                              scene_sent)

                        @state.change(VIEW_SIZE)
                        def on_view_size(**_):
                            size = (state[VIEW_SIZE] or {}).get("size") or {}
                            if size.get("width") and size.get("height"):
                                camera.page_size(size["width"], size["height"])
                                push_page_camera()
                    ctrl.view_reset_camera = view.reset_camera
    push_panel()
    push_scene()
    return server


def serve(session, port: int = 0, host: str = "127.0.0.1", open_browser: bool = True,
          view_mode: str = "auto") -> None:
    """Run the page until Ctrl-C (trame prints the URL)."""
    server = build_app(session, view_mode=view_mode)
    heap.freeze_long_lived()
    server.start(port=port, host=host, open_browser=open_browser, show_connection_info=True)
