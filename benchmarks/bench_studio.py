"""Benchmark: the studio in headless Chromium on the 40-patch benchmark design of
bench_preview.py (targets: slider move -> readout and 3D view drawn, p95 <= 100 ms; add or
move a patch -> check panel updated, p95 <= 150 ms; first load to an interactive page <= 3 s).

Measured from the browser (Debian's chromium driven by Playwright, tests/studio_driver.py):

* ``first_load``: ``page.goto`` in a running browser until the canvas shows the 40 patches
  (the page is interactive: its handlers are bound and the state has arrived; the server is
  already running, its own start (imports, map load, first check and scene) is reported as
  ``server_start``); ``first_scene``: until the 3D view has its first scene as well;
* ``slider_readout``: one step of the fill slider (a key press on its thumb) until the page
  shows the new readout (sent before the check and the scene are recomputed);
* ``slider``: the same step until the 3D view has the new scene (a stamp the server sends
  after the view's data, and the view's own update: vtk.js's scene loaded, or the pushed
  image loaded when the server renders the view), with the server's share of it:
  ``check``, ``scene`` (``preview3d.scene.build_scene`` of the whole design) and ``view_send``
  (serializing the VTK scene for the browser);
* ``slider_check``: the same step until the check panel shows the new check;
* ``move``: a drag of a patch by 4 mm until the check panel shows the new check (the edit
  counter the server sends with it), alternating back and forth; ``move_3d``: until the 3D
  view has the moved patch.

The slider steps go one way (fill up by one slider step each), so every step brings a new
geometry, as a dragged slider does; with ``--alternate`` they go back and forth between two
values, as the benchmark did before: from the third step on the page then has both values'
arrays in vtk.js's cache and fetches none, and the server's check and profile caches hold
them too (a lighter step than a user's).

* ``slider_drawn`` (the target's step): the same step until the frame with the new picture
  has been produced (two animation frames after ``slider``'s end: the WebGL render happens
  after vtk.js's scene-loaded event, an image is painted in the frame after its load);
  ``kB received`` and ``renders``: the websocket bytes the page received (DevTools) and its
  WebGL renders (clears of the canvas) per step.
* ``slider_painted`` (server-rendered view only): the same step until the browser painted the
  view's new image, the ``renderTime`` the Element Timing API reports for it (the time the
  frame with the image was presented). ``slider_drawn``'s two animation frames are a proxy for
  that moment; for an image the browser reports it itself, and it comes about one frame before
  the proxy. A WebGL canvas has no such report. A slider step's image is a draft at half the
  view's width and height (``studio.view3d.image_channel``); ``slider_sharp``: the same step
  until the browser painted the full-size image that follows once the slider rests (0.3 s).
  ``kB received`` and ``browser task`` count both images.

A slider step's readout, check panel and 3D view are watched together in the page
(``WATCH_STEP``), each stamped when it first shows the step, on the clock Python's
``time.time`` reads, from just before the key press: one that arrives later does not delay
another's stamp.

* ``frame_floor``: the least a step's drawn frame can cost here: the page draws the view's
  unchanged scene again (no server, no new arrays: one vtk.js render) until the frame with it
  has been produced, timed in the page; ``next frame, no render``: the same wait with no
  render (the page's own compositing).

Each step starts after ``SETTLE_S`` (the previous frame is done and the view's deferred full
state, ``studio.view3d.view_channel``, has gone out). The 3D view counts as loaded when its
``afterSceneLoaded`` event (vtk.js has synchronized the
scene and fetched the new arrays) has fired for the edit. The server's share: ``check``
(incremental, ``studio.live_check.LiveCheck``), ``scene`` (``preview3d.scene.SceneBuilder``:
only the changed parts are rebuilt), ``sync`` (the pyvista actors of the changed parts),
``view_send`` (trame-vtk serializing the scene state and the new arrays' checksums), each as
wall time and, with the suffix ``cpu``, as the server process's CPU time; ``browser task``:
the page's main-thread task time over the whole step (``BrowserTime``), the browser's share.

``--view browser|server`` measures the 3D view drawn by the browser's WebGL or rendered on the
server (``stitchswitch studio --view``; default ``auto``, as the studio chooses).
``frame_floor`` is measured for the WebGL view only.

The machine is shared: the 1-minute load average is printed with the figures.

    python benchmarks/bench_studio.py [--runs N] [--alternate] [--view MODE] [--json]
"""
from __future__ import annotations

import argparse
import json
import os
import signal
import sys
import tempfile
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(os.path.dirname(HERE), "tests"))
sys.path.insert(0, os.path.join(os.path.dirname(HERE), "src"))

from bench_preview import design_40  # noqa: E402
from stitchswitch.studio.app import VIEW_REF  # noqa: E402
from stitchswitch.studio.view3d.render_mode import MODES  # noqa: E402
from studio_driver import VIEW_UPDATES, browser, studio_server, to_px, view_mode  # noqa: E402

#: the pause before each step, so that the view's deferred full state (``view_channel``) and
#: the previous step's frame are done and do not fall into the step measured
SETTLE_S = 1.3
#: one-way slider steps before the benchmark patch's fill (0.6, step 0.005) reaches 1.0
MAX_ONE_WAY_RUNS = 80
TARGETS = {"slider_drawn": 0.100, "slider_painted": 0.100, "move": 0.150, "first_load": 3.0}
#: counts the page's WebGL renders (one clear of the canvas per render)
COUNT_RENDERS = """(() => {
  for (const C of [WebGLRenderingContext.prototype, WebGL2RenderingContext.prototype]) {
    const clear = C.clear;
    C.clear = function (...args) { window.studioRenders = (window.studioRenders || 0) + 1;
                                   return clear.apply(this, args); };
  }
})();"""
#: resolves after the next frame has been produced (a frame started after this call, then
#: the one after it: the WebGL drawing done before the call is on the screen)
NEXT_FRAME = "new Promise(r => requestAnimationFrame(() => requestAnimationFrame(() => r())))"
#: the floor of a step's frame, timed in the page (ms): the view's unchanged scene drawn again
#: (``setCamera`` with its own camera: one vtk.js render, no new arrays) until the frame with
#: it has been produced (as ``NEXT_FRAME``), and the same wait without a render; null when no
#: render happened (nothing to time)
FRAME_FLOOR = """async () => {
  const view = trame.refs.%s;
  const frame = () => new Promise(r => requestAnimationFrame(() => requestAnimationFrame(() => r())));
  let t = performance.now();
  await frame();
  const idle = performance.now() - t;
  await new Promise(r => setTimeout(r, 300));
  const before = window.studioRenders || 0;
  t = performance.now();
  view.setCamera(view.getCamera());
  while ((window.studioRenders || 0) === before && performance.now() - t < 2000)
    await new Promise(r => setTimeout(r, 0));
  await frame();
  return [(window.studioRenders || 0) > before ? performance.now() - t : null, idle];
}"""


def _stamp(page, sel: str) -> int:
    return int(page.locator(sel).inner_text() or 0)


def _wait_stamp(page, sel: str, above: int) -> None:
    # textContent, not innerText: the poll runs every frame inside the step measured, and
    # innerText makes the page recalculate its style (1-2 ms of main-thread time a frame)
    page.wait_for_function(f"Number(document.querySelector('{sel}').textContent) > {above}",
                           polling="raf", timeout=30000)


def _renders(page) -> int:
    return int(page.evaluate("window.studioRenders || 0"))


def _loads(page) -> int:
    return int(page.evaluate(VIEW_UPDATES[view_mode(page)]))


def _wait_scene(page, above: int, loads: int) -> None:
    """Until the 3D view shows edit ``above + 1`` or later: the server has sent its scene (the
    scene stamp follows the view's data on the websocket), and the view has updated since
    ``loads`` and is not synchronizing any more (the browser's WebGL: vtk.js's
    afterSceneLoaded, arrays fetched; rendered on the server: the image pushed after the edit
    has loaded)."""
    mode = view_mode(page)
    busy = " && !window.studioSceneBusy" if mode == "browser" else ""
    page.wait_for_function(
        f"Number(document.querySelector('#scene-stamp').textContent) > {above} && "
        f"{VIEW_UPDATES[mode]} > {loads}{busy}", polling="raf", timeout=30000)


#: watches one step in the page: every animation frame it checks whether the readout, the
#: check panel and the 3D view show the edit after ``before`` (the view: ``loads`` exceeded and
#: the scene stamp, as ``_wait_scene``), stamps each the first time it does (ms since the epoch,
#: the clock Python's ``time.time`` reads too) and the 3D view's frame as drawn two animation
#: frames after it is loaded (as ``NEXT_FRAME``); with ``painted`` (an image pushed by the
#: server), also the time the browser painted the view's new image (``studioImagePaints``,
#: studio_driver.COUNT_VIEW_IMAGES) and the time it painted the first full-size one (``sharp``:
#: a dragged slider's images are drafts until it rests); ``window.studioMarks.done`` when all
#: are in.
#: The conditions are watched together, so one that comes later (a check sent after the
#: view) does not delay another's stamp.
WATCH_STEP = """([before, loadsExpr, loads, busy, painted]) => {
  const now = () => performance.timeOrigin + performance.now();
  const start = now();
  const num = sel => Number(document.querySelector(sel).textContent);
  const loaded = new Function('return ' + loadsExpr);
  const marks = window.studioMarks = {};
  const poll = () => {
    if (!marks.readout && num('#readout-stamp') > before) marks.readout = now();
    if (!marks.check && num('#edits') > before) marks.check = now();
    if (!marks.scene && num('#scene-stamp') > before && loaded() > loads
        && !(busy && window.studioSceneBusy)) {
      marks.scene = now();
      requestAnimationFrame(() => requestAnimationFrame(() => { marks.drawn = now(); }));
    }
    if (painted && marks.scene && !marks.painted)
      marks.painted = (window.studioImagePaints.find(([t]) => t >= start) || [])[0];
    if (painted && marks.painted && !marks.sharp) {
      const img = document.querySelector('#view3d img');
      const full = Math.round(img.clientWidth * devicePixelRatio) - 1;
      marks.sharp = (window.studioImagePaints.find(([t, w]) => t >= start && w >= full) || [])[0];
    }
    if (marks.readout && marks.check && marks.drawn && (marks.sharp || !painted))
      marks.done = true;
    else requestAnimationFrame(poll);
  };
  requestAnimationFrame(poll);
}"""


class Received:
    """The websocket bytes the page receives (DevTools ``Network.webSocketFrameReceived``; a
    binary frame's payload arrives base64-encoded, counted as its decoded size)."""

    def __init__(self, page):
        self.cdp = page.context.new_cdp_session(page)
        self.cdp.send("Network.enable")
        self.bytes = 0
        self.frames = 0
        self.cdp.on("Network.webSocketFrameReceived", self._on)

    def _on(self, event) -> None:
        r = event["response"]
        n = len(r["payloadData"])
        self.bytes += n * 3 // 4 if r.get("opcode") == 2 else n
        self.frames += 1


class BrowserTime:
    """The page's main-thread task time (Chrome DevTools ``Performance.getMetrics``
    ``TaskDuration``, seconds): the browser's own work, much less sensitive to the machine's
    load than wall time."""

    def __init__(self, page):
        self.cdp = page.context.new_cdp_session(page)
        self.cdp.send("Performance.enable")

    def __call__(self) -> float:
        metrics = self.cdp.send("Performance.getMetrics")["metrics"]
        return next(m["value"] for m in metrics if m["name"] == "TaskDuration")


def measure(runs: int, alternate: bool = False, where: str = "auto") -> dict:
    from stitchswitch.layout.garment.design_io import load_design
    from stitchswitch.studio.canvas import view_of

    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "design40.json")
        design_40(path)
        design = load_design(path)
        view = view_of(design)
        t0 = time.perf_counter()
        with studio_server(path, view=where) as (url, _):
            server_start = time.perf_counter() - t0
            with browser() as ctx:
                page = ctx.new_page()
                page.add_init_script(COUNT_RENDERS)
                t1 = time.perf_counter()
                page.goto(url)
                page.wait_for_function("document.querySelectorAll('#canvas circle').length == 40",
                                       polling="raf", timeout=60000)
                first_load = time.perf_counter() - t1
                page.wait_for_selector("#view-mode-key", state="attached")
                mode = view_mode(page)
                _wait_scene(page, -1, 0)
                first_scene = time.perf_counter() - t1
                p = design.patches[0]
                page.mouse.click(*to_px(page, view, *p.centre_mm))
                page.wait_for_selector("#slider-fill .v-slider-thumb")
                thumb = page.locator("#slider-fill .v-slider-thumb")
                thumb.focus()
                task, received = BrowserTime(page), Received(page)
                slider, readout, check, server, slider_task, move_task = [], [], [], [], [], []
                drawn, painted, sharp, kbytes, renders = [], [], [], [], []
                for k in range(runs):
                    time.sleep(SETTLE_S)
                    before, loads = _stamp(page, "#edits"), _loads(page)
                    b0, r0, n0 = task(), received.bytes, _renders(page)
                    page.evaluate(WATCH_STEP, [before, VIEW_UPDATES[mode], loads, mode == "browser",
                                               mode == "server"])
                    t = time.time()
                    page.keyboard.press("ArrowLeft" if alternate and k % 2 else "ArrowRight")
                    page.wait_for_function("window.studioMarks.done === true", timeout=30000)
                    marks = page.evaluate("window.studioMarks")
                    readout.append(marks["readout"] / 1000.0 - t)
                    check.append(marks["check"] / 1000.0 - t)
                    slider.append(marks["scene"] / 1000.0 - t)
                    drawn.append(marks["drawn"] / 1000.0 - t)
                    if mode == "server":
                        painted.append(marks["painted"] / 1000.0 - t)
                        sharp.append(marks["sharp"] / 1000.0 - t)
                    slider_task.append(task() - b0)
                    kbytes.append((received.bytes - r0) / 1000.0)
                    renders.append(_renders(page) - n0)
                    server.append(json.loads(page.locator("#timings").inner_text()))
                floor, floor_idle = [], []
                for _ in range(runs if mode == "browser" else 0):     # the WebGL frame
                    time.sleep(SETTLE_S)
                    render_ms, idle_ms = page.evaluate(FRAME_FLOOR % VIEW_REF)
                    if render_ms is not None:
                        floor.append(render_ms / 1000.0)
                    floor_idle.append(idle_ms / 1000.0)
                move, move_3d = [], []
                x, y = p.centre_mm
                for k in range(runs):
                    dx = 4.0 if k % 2 == 0 else -4.0
                    time.sleep(SETTLE_S)
                    before, loads = _stamp(page, "#edits"), _loads(page)
                    page.mouse.move(*to_px(page, view, x, y))
                    page.mouse.down()
                    page.mouse.move(*to_px(page, view, x + dx, y), steps=2)
                    b0 = task()
                    t = time.perf_counter()
                    page.mouse.up()
                    _wait_stamp(page, "#edits", before)
                    move.append(time.perf_counter() - t)
                    _wait_scene(page, before, loads)
                    page.evaluate(NEXT_FRAME)
                    move_3d.append(time.perf_counter() - t)
                    move_task.append(task() - b0)
                    server.append(json.loads(page.locator("#timings").inner_text()))
                    x += dx
    slider_rows, move_rows = server[:runs], server[runs:]
    phases = {f"  server {k[:-2]}": [row[k] / 1000.0 for row in slider_rows]
              for k in slider_rows[0] if k.endswith("_s")}
    move_phases = {f"  server {k[:-2]}": [row[k] / 1000.0 for row in move_rows]
                   for k in move_rows[0] if k.endswith("_s")}
    return {"view_mode": mode, "server_start": [server_start], "first_load": [first_load],
            "first_scene": [first_scene], "slider_readout": readout,
            "slider_check": check, "slider": slider, "slider_drawn": drawn,
            "slider_painted": painted or [float("nan")],
            "slider_sharp": sharp or [float("nan")],
            "  browser task (slider)": slider_task, "  kB received (slider)": kbytes,
            "  renders (slider)": renders,
            "frame_floor": floor or [float("nan")],
            "  next frame, no render": floor_idle or [float("nan")],
            **phases, "move": move, "move_3d": move_3d, "  browser task (move)": move_task,
            **{k + " (move)": v for k, v in move_phases.items()}}


#: counts and kB, not seconds: printed as they are (their "median_s" and "p95_s" in --json
#: are in the row's "unit")
COUNTS = ("  kB received (slider)", "  renders (slider)")


def summary(samples: dict) -> list[dict]:
    rows = []
    for name, xs in samples.items():
        xs = np.asarray(xs)
        target = TARGETS.get(name)
        stat = float(np.percentile(xs, 95)) if len(xs) > 1 else float(xs[0])
        rows.append({"step": name, "unit": "kB" if "kB" in name else ("count" if name in COUNTS
                                                                      else "s"),
                     "runs": int(xs.size), "median_s": float(np.median(xs)),
                     "p95_s": stat, "target_s": target,
                     "meets": None if target is None or np.isnan(stat) else bool(stat <= target)})
    return rows


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--runs", type=int, default=30)
    ap.add_argument("--alternate", action="store_true",
                    help="slider steps back and forth between two values (cached arrays)")
    ap.add_argument("--view", default="auto", choices=MODES,
                    help="where the 3D view is drawn (stitchswitch studio --view)")
    ap.add_argument("--json", action="store_true")
    args = ap.parse_args(argv)
    if not args.alternate and not 1 <= args.runs <= MAX_ONE_WAY_RUNS:
        ap.error(f"--runs {args.runs}: 1..{MAX_ONE_WAY_RUNS} one way (the fill slider ends at "
                 "1.0), or --alternate")
    # a terminated benchmark unwinds like Ctrl-C, so the studio server it started is stopped
    signal.signal(signal.SIGTERM, lambda *_: sys.exit(143))
    samples = measure(args.runs, args.alternate, args.view)
    mode = samples.pop("view_mode")
    rows = summary(samples)
    load = os.getloadavg()[0]
    if args.json:
        print(json.dumps({"rows": rows, "loadavg_1min": load, "alternate": args.alternate,
                          "view_mode": mode}, indent=2))
        return 0
    print(f"3D view: {'rendered on the server' if mode == 'server' else 'WebGL in the browser'}")
    print(f"{'step':<30}{'runs':>5}{'median ms':>11}{'p95 ms':>9}{'target ms':>11}  meets")
    for r in rows:
        tgt = "" if r["target_s"] is None else f"{1000 * r['target_s']:.0f}"
        scale = 1 if r["step"] in COUNTS else 1000
        print(f"{r['step']:<30}{r['runs']:>5}{scale * r['median_s']:>11.0f}{scale * r['p95_s']:>9.0f}"
              f"{tgt:>11}  {'' if r['meets'] is None else ('yes' if r['meets'] else 'NO')}")
    print(f"load average (1 min): {load:.2f}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
