"""Drive ``stitchswitch studio`` in Debian's chromium through Playwright (the end-to-end test
and benchmarks/bench_studio.py): start the server on a free port, open a fresh headless
browser on it, and map garment mm to pixels on the canvas. Nothing is downloaded: the browser
is the system's /usr/bin/chromium."""
from __future__ import annotations

import contextlib
import os
import shutil
import socket
import subprocess
import sys
import tempfile
import time

CHROMIUM = "/usr/bin/chromium"
ARGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
        "--disable-background-networking", "--disable-component-update", "--disable-sync"]


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


#: counts the images the server-rendered 3D view has loaded (``window.studioImageLoads``):
#: trame-vtk's remote view shows each pushed image in an ``img`` inside ``#view3d``; and
#: collects the times the browser painted them and their widths (``window.studioImagePaints``,
#: ``[epoch ms, px]``: the Element Timing API's ``renderTime`` and ``naturalWidth`` of each
#: image, for which the ``img`` is marked)
COUNT_VIEW_IMAGES = """(() => {
  const src = Object.getOwnPropertyDescriptor(HTMLImageElement.prototype, 'src');
  Object.defineProperty(HTMLImageElement.prototype, 'src', {
    configurable: true,
    get() { return src.get.call(this); },
    set(value) {
      this.setAttribute('elementtiming', 'studio-image');
      this.addEventListener('load', () => {
        if (this.closest('#view3d')) window.studioImageLoads = (window.studioImageLoads || 0) + 1;
      }, {once: true});
      src.set.call(this, value);
    }});
  window.studioImagePaints = [];
  new PerformanceObserver((list) => {
    for (const e of list.getEntries())
      if (e.element && e.element.closest('#view3d'))
        window.studioImagePaints.push([performance.timeOrigin + e.renderTime, e.naturalWidth]);
  }).observe({type: 'element'});
})();"""


#: the page's count of the 3D view's updates, by where it is drawn: vtk.js's scene loads
#: (WebGL in the browser, counted by the page) or the images the server pushed
#: (``COUNT_VIEW_IMAGES``)
VIEW_UPDATES = {"browser": "(window.studioSceneLoads || 0)",
                "server": "(window.studioImageLoads || 0)"}


#: whether the server-rendered view shows a full-size image, not a dragged slider's draft
#: (``studio.view3d.image_channel``): the image's width is the view's in device pixels
FULL_SIZE_IMAGE = """(() => {
  const img = document.querySelector('#view3d img');
  return !!img && img.naturalWidth >= Math.round(img.clientWidth * devicePixelRatio) - 1;
})()"""


def view_mode(page) -> str:
    """Where the page's 3D view is drawn: ``browser`` or ``server``."""
    return page.locator("#view-mode-key").text_content()


@contextlib.contextmanager
def studio_server(design_path, timeout_s: float = 60.0, view: str = "auto"):
    """The URL of a running ``stitchswitch studio DESIGN --no-browser --view VIEW``; stopped
    with SIGINT (Ctrl-C) at the end, which must end it cleanly."""
    port = free_port()
    env = dict(os.environ)
    src = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "src")
    env["PYTHONPATH"] = src + os.pathsep + env.get("PYTHONPATH", "")
    proc = subprocess.Popen([sys.executable, "-m", "stitchswitch", "studio", os.fspath(design_path),
                             "--no-browser", "--port", str(port), "--view", view], env=env,
                            stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    url = f"http://127.0.0.1:{port}/"
    deadline = time.monotonic() + timeout_s
    lines = []
    try:
        while time.monotonic() < deadline:
            line = proc.stdout.readline()
            if not line and proc.poll() is not None:
                raise RuntimeError("the studio stopped:\n" + "".join(lines))
            lines.append(line)
            if "App running at" in line:
                break
        else:
            raise RuntimeError("the studio did not start:\n" + "".join(lines))
        yield url, lines
    finally:
        import signal

        proc.send_signal(signal.SIGINT)
        try:
            rest, _ = proc.communicate(timeout=20)
            lines.append(rest or "")
        except subprocess.TimeoutExpired:
            proc.kill()
            proc.communicate()
            raise
        lines.append(f"exit code {proc.returncode}\n")


@contextlib.contextmanager
def browser(size=(1400, 850)):
    """A fresh headless Chromium (its own temporary profile): the browser context."""
    from playwright.sync_api import sync_playwright

    profile = tempfile.mkdtemp(prefix="studio-chromium-")
    try:
        with sync_playwright() as p:
            ctx = p.chromium.launch_persistent_context(profile, executable_path=CHROMIUM, args=ARGS,
                                                       headless=True,
                                                       viewport={"width": size[0], "height": size[1]})
            ctx.add_init_script(COUNT_VIEW_IMAGES)
            try:
                yield ctx
            finally:
                ctx.close()
    finally:
        shutil.rmtree(profile, ignore_errors=True)


@contextlib.contextmanager
def browser_page(url, size=(1400, 850)):
    """A page of a fresh browser on ``url``, once the canvas shows the pieces."""
    with browser(size) as ctx:
        page = ctx.new_page()
        page.goto(url)
        page.wait_for_selector("#canvas svg circle, #canvas svg polygon", timeout=30000)
        yield page


def to_px(page, view, x_mm: float, y_mm: float) -> tuple[float, float]:
    """Page pixels of garment point (x_mm, y_mm) on the canvas (inverse of ``canvas.to_mm``)."""
    box = page.locator("#canvas").bounding_box()
    scale = min(box["width"] / view.width, box["height"] / view.height)
    ox = (box["width"] - view.width * scale) / 2.0
    oy = (box["height"] - view.height * scale) / 2.0
    return (box["x"] + ox + (x_mm - view.x0) * scale, box["y"] + oy + (-y_mm - view.y0) * scale)


def drag(page, start, end, steps: int = 5) -> None:
    page.mouse.move(*start)
    page.mouse.down()
    page.mouse.move(*end, steps=steps)
    page.mouse.up()
