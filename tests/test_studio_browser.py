"""End to end in a real browser (Debian's chromium through Playwright): the studio on the tennis-
pocket demo design; add a patch by clicking on the piece, delete it with the Delete key and
undo, drag it, zoom, hold it to see the edge rule, multi-select, move the fill slider and see
the readout and the 3D view change, run inverse design, apply a candidate and place one where
the next click lands, drag a patch over the piece edge and see the violation appear and
clear, save and check the saved file with ``stitchswitch check``, then group into hoopings and
export a JEF that the tests' own decoder reads back with the expected extent. With
STUDIO_SCREENSHOTS=DIR the screenshots of docs/studio.md are written to DIR."""
import json
import os
import re
import shutil

import numpy as np
import pytest
from click.testing import CliRunner

from stitchswitch.cli.main import cli
from stitchswitch.layout.garment.design_io import load_design, save_design

from decoders import jef

pytest.importorskip("playwright")
pytest.importorskip("trame")
pytest.importorskip("trame_vtk")
from stitchswitch.studio.canvas import view_of  # noqa: E402
from studio_driver import (  # noqa: E402
    CHROMIUM,
    FULL_SIZE_IMAGE,
    VIEW_UPDATES,
    browser_page,
    drag,
    studio_server,
    to_px,
    view_mode,
)

pytestmark = [pytest.mark.slow,
              pytest.mark.skipif(not os.path.exists(CHROMIUM), reason=f"{CHROMIUM} is not installed "
                                 "(.ci/run installs it with apt-get)")]


def shot(page, tmp_path, name):
    path = tmp_path / f"studio-{name}.png"
    page.screenshot(path=str(path))
    out = os.environ.get("STUDIO_SCREENSHOTS")
    if out:
        os.makedirs(out, exist_ok=True)
        shutil.copy(path, os.path.join(out, path.name))


def readout_h(page) -> float:
    return float(re.match(r"h (-?[\d.]+) mm", page.locator("#readout").inner_text()).group(1))


def scene_loads(page) -> int:
    return int(page.evaluate(VIEW_UPDATES[view_mode(page)]))


def wait_scene(page, loads: int) -> None:
    """Until the 3D view shows a newer scene than the one counted in ``loads``."""
    busy = " && !window.studioSceneBusy" if view_mode(page) == "browser" else ""
    page.wait_for_function(f"{VIEW_UPDATES[view_mode(page)]} > {loads}{busy}", timeout=60000)


def check_software_view(page) -> None:
    """Headless chromium has no GPU, nor has this machine: the view is rendered on the server
    when the page was left to choose (``--view auto``); a WebGL view's context is software and
    single-sampled."""
    page.wait_for_selector("#view3d canvas, #view3d img", state="attached")
    if view_mode(page) == "server":
        assert "rendered on the server" in page.locator("#view-mode").inner_text()
        page.wait_for_function("window.studioImageLoads > 0", timeout=60000)
        assert page.locator("#view3d img[src^='blob:']").count() == 1     # the pushed image
        return
    page.wait_for_selector("#view3d canvas")
    assert "SwiftShader" in page.evaluate("window.studioSoftwareGL")
    assert page.evaluate("document.querySelector('#view3d canvas').getContext('webgl2')"
                         ".getContextAttributes().antialias") is False


def demo_design(tmp_path):
    """The tennis-pocket demo's design, the file it is saved to and its canvas view."""
    from stitchswitch.demos.tennis_pocket import build

    design = build().design
    path = tmp_path / "tennis-pocket.json"
    save_design(design, path)
    return design, path, view_of(design)


def errors(page) -> int:
    return int(re.search(r"Constraints: (\d+) error", page.locator("#check-title").inner_text()).group(1))


def test_studio_in_chromium(tmp_path):
    design, path, view = demo_design(tmp_path)
    with studio_server(path) as (url, log):
        with browser_page(url) as page:
            circles = page.locator("#canvas circle")
            assert circles.count() == 1
            shot(page, tmp_path, "open")
            check_software_view(page)
            from stitchswitch.studio.view3d import render_mode
            assert view_mode(page) == render_mode.choose("auto")
            # add a patch by clicking on an empty spot of the piece: it becomes the selection
            page.mouse.click(*to_px(page, view, 60.0, 150.0))
            page.wait_for_function("document.querySelectorAll('#canvas circle').length == 2")
            assert page.locator("#inspector-title").inner_text() == "Patch p1"
            # Delete removes it, undo brings it back
            page.keyboard.press("Delete")
            page.wait_for_function("document.querySelectorAll('#canvas circle').length == 1")
            page.locator("#undo").click()
            page.wait_for_function("document.querySelectorAll('#canvas circle').length == 2")
            # drag it 40 mm to the right
            drag(page, to_px(page, view, 60.0, 150.0), to_px(page, view, 100.0, 150.0))
            page.wait_for_function("Number(document.querySelector('#canvas circle[data-patch=p1]')"
                                   ".getAttribute('cx')) > 90")
            # zoom in on the canvas and back (toolbar), the rulers follow
            box0 = page.locator("#canvas svg").first.get_attribute("viewBox")
            page.locator("#zoom-in").click()
            page.wait_for_function(f"document.querySelector('#canvas svg').getAttribute('viewBox') != '{box0}'")
            assert float(page.locator("#canvas svg").first.get_attribute("viewBox").split()[2]) < float(box0.split()[2])
            assert page.locator("#canvas [data-ruler-x]").count() > 2
            page.locator("#fit-view").click()
            page.wait_for_function(f"document.querySelector('#canvas svg').getAttribute('viewBox') == '{box0}'")
            # holding the patch draws the piece-edge rule, and the patch follows the pointer
            # while the button is down; releasing where it was pressed changes nothing
            edits = int(page.locator("#edits").inner_text())
            page.mouse.move(*to_px(page, view, 100.0, 150.0))
            page.mouse.down()
            page.wait_for_selector("#canvas [data-guide=centre]")
            page.mouse.move(*to_px(page, view, 130.0, 140.0), steps=6)
            page.wait_for_function("Number(document.querySelector('#canvas circle[data-patch=p1]')"
                                   ".getAttribute('cx')) > 125")
            assert page.locator("#canvas [data-guide=centre][data-guide-patch=p1]").count() >= 1
            assert int(page.locator("#edits").inner_text()) == edits          # not an edit yet
            page.mouse.move(*to_px(page, view, 100.0, 150.0), steps=6)
            page.wait_for_function("Math.abs(Number(document.querySelector('#canvas circle"
                                   "[data-patch=p1]').getAttribute('cx')) - 100) < 1.5")
            page.wait_for_timeout(200)
            page.mouse.up()
            page.wait_for_function("!document.querySelector('#canvas [data-guide]')")
            cx = float(page.locator("#canvas circle[data-patch=p1]").get_attribute("cx"))
            assert cx == pytest.approx(100.0, abs=1.5)
            # Shift+click adds the pocket to the selection, Shift+click again takes it out
            pocket = design.patches[0]
            page.keyboard.down("Shift")
            page.mouse.click(*to_px(page, view, *pocket.centre_mm))
            page.keyboard.up("Shift")
            page.wait_for_selector("#multi")
            page.keyboard.down("Shift")
            page.mouse.click(*to_px(page, view, *pocket.centre_mm))
            page.keyboard.up("Shift")
            page.wait_for_function("!document.querySelector('#multi')")
            page.mouse.click(*to_px(page, view, 100.0, 150.0))
            page.wait_for_function("document.querySelector('#inspector-title').innerText == 'Patch p1'")
            # the fill slider: the readout and the 3D view change
            h0 = readout_h(page)
            before = page.locator("#view3d").screenshot()
            loads = scene_loads(page)
            thumb = page.locator("#slider-fill .v-slider-thumb")
            thumb.focus()
            for _ in range(30):
                page.keyboard.press("ArrowRight")
            page.wait_for_function(f"!document.querySelector('#readout').innerText.startsWith('h {h0} ')")
            wait_scene(page, loads)
            if view_mode(page) == "server":         # the slider's drafts, then full size
                page.wait_for_function(FULL_SIZE_IMAGE, timeout=10000)
            page.wait_for_timeout(500)
            assert readout_h(page) != h0
            assert page.locator("#view3d").screenshot() != before
            assert page.locator("#profile polyline").count() == 1        # the profile plot
            shot(page, tmp_path, "design")
            # inverse design for h = 12 mm, applied to the selected patch
            page.locator("#target-h input").fill("12")
            page.locator("#run-inverse").click()
            page.locator(".apply-candidate").first.wait_for(timeout=60000)
            shot(page, tmp_path, "inverse")
            h1 = readout_h(page)
            page.locator(".apply-candidate").first.click()
            page.wait_for_function(f"!document.querySelector('#readout').innerText.startsWith('h {h1} ')")
            assert readout_h(page) == pytest.approx(12.0, abs=0.25), page.locator("#message").inner_text()
            assert errors(page) == 0
            # "Place" a candidate where the next click lands: a third patch there, then undo
            page.locator(".place-candidate").first.click()
            page.wait_for_function("/click on a piece/.test(document.querySelector('#message').innerText)")
            page.mouse.click(*to_px(page, view, -100.0, 100.0))
            page.wait_for_function("document.querySelectorAll('#canvas circle').length == 3")
            assert readout_h(page) == pytest.approx(12.0, abs=0.25)
            page.locator("#undo").click()
            page.wait_for_function("document.querySelectorAll('#canvas circle').length == 2")
            page.mouse.click(*to_px(page, view, 100.0, 150.0))
            page.wait_for_function("document.querySelector('#inspector-title').innerText == 'Patch p1'")
            # over the piece edge (the waist): a violation, then undo clears it
            top = float(design.pieces[0].outline_mm[:, 1].max())
            loads = scene_loads(page)
            drag(page, to_px(page, view, 100.0, 150.0), to_px(page, view, 100.0, top - 5.0))
            page.wait_for_function("/Constraints: [1-9]/.test(document.querySelector('#check-title').innerText)")
            assert page.locator(".violation").count() >= 1
            wait_scene(page, loads)                    # the 3D view draws it flagged too
            shot(page, tmp_path, "violation")
            page.locator("#undo").click()
            page.wait_for_function("/Constraints: 0 /.test(document.querySelector('#check-title').innerText)")
            # save, and the CLI's check accepts the saved file
            page.locator("#save").click()
            page.wait_for_function("document.querySelector('#dirty').innerText == 'saved'")
            saved = load_design(path)
            assert [p.id for p in saved.patches] == ["pocket1", "p1"]
            assert saved.patch("p1").centre_mm[0] == pytest.approx(100.0, abs=3.0)
            r = CliRunner().invoke(cli, ["check", str(path)])
            assert r.exit_code == 0, r.output
            # ... and the panel shows the small-pieces warnings check prints, word for word
            assert page.locator(".small-pieces").all_inner_texts() == [
                ln for ln in r.output.splitlines() if ln.startswith("warning: ")]
            # Fabrication Mode: group and export; the JEF read back by the independent decoder
            page.locator("#mode-fabrication").click()
            page.locator("#group").click()
            page.locator(".hooping").first.wait_for(timeout=60000)
            out = tmp_path / "fabrication"
            page.locator("#export-dir input").fill(str(out))
            page.locator("#export").click()
            page.locator(".exported").first.wait_for(timeout=120000)
            # the first hooping's stitch plan, and a download of its machine file from the page
            page.locator(".hooping").first.click()
            page.wait_for_selector("#plan-svg polyline", timeout=60000)
            assert int(re.search(r"(\d+) stitches", page.locator("#plan-counts").inner_text()).group(1)) > 100
            shot(page, tmp_path, "fabrication")
            link = page.locator(".download", has_text=re.compile(r"hoop0?1\.jef"))
            with page.expect_download() as dl:
                link.click()
            downloaded = tmp_path / "downloaded.jef"
            dl.value.save_as(downloaded)
    assert log[-1] == "exit code 0\n"            # Ctrl-C (SIGINT) stopped it cleanly
    sheet = json.loads((out / "fabrication.json").read_text())
    first = sheet["hoopings"][0]["files"]["embroidery"]
    assert downloaded.read_bytes() == (out / first).read_bytes()
    assert sorted(p["id"] for h in sheet["hoopings"] for p in h["patches"]) == ["p1", "pocket1"]
    for h in sheet["hoopings"]:
        # the stitches span the hooping's patches: centres in hoop mm +- d / 2 (0.1 mm units)
        xy = np.array([(x, y) for kind, x, y in jef.decode((out / h["files"]["embroidery"]).read_bytes()).records
                       if kind == "stitch"]) / 10.0
        pos = np.array([p["position_hoop_mm"] for p in h["patches"]])
        rad = np.array([p["diameter_mm"] / 2 for p in h["patches"]])[:, None]
        expected = (pos + rad).max(axis=0) - (pos - rad).min(axis=0)
        assert np.ptp(xy, axis=0) == pytest.approx(expected, abs=1.5)


@pytest.mark.parametrize("mode", ["browser", "server"])
def test_either_view_follows_the_fill_slider(tmp_path, mode):
    """``--view browser`` (vtk.js draws the scene's arrays in WebGL) and ``--view server`` (VTK
    renders on the server, the page shows its images): a fill step changes the readout and the
    picture of the 3D view, and dragging in the view rotates it."""
    design, path, view = demo_design(tmp_path)
    with studio_server(path, view=mode) as (url, _):
        with browser_page(url) as page:
            assert view_mode(page) == mode
            check_software_view(page)
            wait_scene(page, 0)
            page.mouse.click(*to_px(page, view, *design.patches[0].centre_mm))
            page.wait_for_selector("#slider-fill .v-slider-thumb")
            h0 = readout_h(page)
            page.wait_for_timeout(1500)                 # the selection's scene, if any, is in
            before, loads = page.locator("#view3d").screenshot(), scene_loads(page)
            page.locator("#slider-fill .v-slider-thumb").focus()
            for _ in range(10):
                page.keyboard.press("ArrowRight")
            wait_scene(page, loads)
            page.wait_for_function(f"!document.querySelector('#readout').innerText.startsWith('h {h0} ')")
            # the check panel catches up with the last step (rendered on the server, the check
            # waits until the page draws the step's image)
            page.wait_for_function("Number(document.querySelector('#readout-stamp').textContent)"
                                   " > 0 && document.querySelector('#edits').textContent === "
                                   "document.querySelector('#readout-stamp').textContent")
            if mode == "server":
                # the steps' images are drafts at half size, and a full-size image follows
                # once the slider rests
                page.wait_for_function(FULL_SIZE_IMAGE, timeout=10000)
                widths = page.evaluate("window.studioImagePaints.map(([t, w]) => w)")
                assert min(widths) <= max(widths) // 2 + 1, widths
            page.wait_for_timeout(500)
            after = page.locator("#view3d").screenshot()
            assert after != before
            box = page.locator("#view3d").bounding_box()
            cx, cy = box["x"] + box["width"] / 2, box["y"] + box["height"] / 2
            drag(page, (cx, cy), (cx + 120, cy + 40), steps=8)
            page.wait_for_timeout(1000)
            assert page.locator("#view3d").screenshot() != after


#: the rows and columns at the 3D view's edges left out of ``design_margins``
EDGE_PX = 6


def design_margins(png: bytes) -> tuple[int, int, int, int]:
    """Pixels between the drawn design (anything not the white background) and the image's
    left, top, right and bottom edges, less ``EDGE_PX`` (the toolbar's shadow falls on the
    view's top rows); zero where the design runs off an edge."""
    import io

    from PIL import Image

    img = np.asarray(Image.open(io.BytesIO(png)).convert("RGB"))[EDGE_PX:-EDGE_PX, EDGE_PX:-EDGE_PX]
    drawn = (img < 235).any(axis=2)
    rows, cols = np.where(drawn.any(axis=1))[0], np.where(drawn.any(axis=0))[0]
    assert rows.size and cols.size, "the 3D view is blank"
    h, w = drawn.shape
    return int(cols[0]), int(rows[0]), int(w - 1 - cols[-1]), int(h - 1 - rows[-1])


def wait_picture(page, accept, timeout_ms: int = 20000) -> bytes:
    """The 3D view's screenshot once ``accept(png)`` holds (the camera's fit reaches the page
    a moment after its size), or the last one, which fails ``accept``."""
    png = page.locator("#view3d").screenshot()
    for _ in range(timeout_ms // 250):
        if accept(png):
            break
        page.wait_for_timeout(250)
        png = page.locator("#view3d").screenshot()
    return png


@pytest.mark.parametrize("mode", ["browser", "server"])
def test_the_3d_view_shows_the_whole_design_at_the_size_the_page_gives(tmp_path, mode):
    """The camera is fitted to the page's view: the whole design in view at first and after
    the window is made narrower; once the user has turned the view it stays as they left it
    through changes of size, and "Fit 3D" brings back the fitted view."""
    from stitchswitch.demos.tennis_pocket import build

    path = tmp_path / "tennis-pocket.json"
    save_design(build().design, path)
    inside = lambda png: min(design_margins(png)) > 0                  # noqa: E731
    with studio_server(path, view=mode) as (url, _):
        with browser_page(url) as page:
            assert view_mode(page) == mode
            wait_scene(page, 0)
            assert inside(wait_picture(page, inside)), design_margins(
                page.locator("#view3d").screenshot())
            page.set_viewport_size({"width": 1000, "height": 850})
            fitted = wait_picture(page, inside)
            assert inside(fitted), design_margins(fitted)
            page.wait_for_timeout(1000)
            fitted = page.locator("#view3d").screenshot()
            box = page.locator("#view3d").bounding_box()
            cx, cy = box["x"] + box["width"] / 2, box["y"] + box["height"] / 2
            drag(page, (cx, cy), (cx + 120, cy + 40), steps=8)
            turned = wait_picture(page, lambda png: png != fitted)
            assert turned != fitted
            page.set_viewport_size({"width": 1100, "height": 850})
            page.wait_for_timeout(1500)
            page.set_viewport_size({"width": 1000, "height": 850})
            page.wait_for_timeout(1500)
            assert page.locator("#view3d").screenshot() != fitted     # still the user's view
            page.locator("#fit-3d").click()
            # the fitted view's outline again (vtk.js leaves its lights where the rotation put
            # them until the next one: the shading may differ in the browser's WebGL view)
            same = lambda png: design_margins(png) == design_margins(fitted)   # noqa: E731
            back = wait_picture(page, same)
            assert design_margins(back) == design_margins(fitted)


BUSY_VISIBLE = "getComputedStyle(document.querySelector('#busy')).visibility === 'visible'"


def test_the_working_note_shows_only_once_a_call_has_lasted(tmp_path):
    """No spinning progress circle on the page (trame's footer: it was animated for every call,
    a slider step's included); the "working..." note in the page's corner stays hidden through
    short calls and shows once the page's busy flag (``trame__busy``, which trame's client sets
    while a call is in flight) has been up for ``BUSY_AFTER_S``, and goes again when it drops."""
    import time

    from stitchswitch.studio.app import BUSY_AFTER_S

    design, path, view = demo_design(tmp_path)
    with studio_server(path) as (url, _):
        with browser_page(url) as page:
            assert page.locator(".v-progress-circular").count() == 0
            assert not page.locator("footer").is_visible()
            page.wait_for_function(f"!({BUSY_VISIBLE})", timeout=10000)   # the load's calls
            # warm slider steps' calls are short: the note never shows (the first step after
            # the selection may fill the server's caches, and is left out)
            page.mouse.click(*to_px(page, view, *design.patches[0].centre_mm))
            page.wait_for_selector("#slider-fill .v-slider-thumb")
            page.locator("#slider-fill .v-slider-thumb").focus()
            page.keyboard.press("ArrowRight")
            page.wait_for_timeout(1500)
            page.wait_for_function(f"!({BUSY_VISIBLE})", timeout=10000)
            page.evaluate("window.studioBusySeen = false; window.studioBusyWatch = setInterval("
                          f"() => {{ if ({BUSY_VISIBLE}) window.studioBusySeen = true }}, 20)")
            for _ in range(3):
                edits = int(page.locator("#edits").inner_text())
                page.keyboard.press("ArrowRight")
                page.wait_for_function(f"Number(document.querySelector('#edits').textContent) > {edits}")
                page.wait_for_timeout(800)
            assert page.evaluate("clearInterval(window.studioBusyWatch) || window.studioBusySeen") is False
            # a call that lasts: the flag up, as trame's client raises it while a call is pending
            page.evaluate("trame.state.set('trame__busy', 1)")
            t0 = time.perf_counter()
            page.wait_for_function(BUSY_VISIBLE, timeout=5000)
            assert time.perf_counter() - t0 >= BUSY_AFTER_S - 0.05
            # on screen and on top (not under the drawer)
            box = page.locator("#busy").bounding_box()
            assert box["x"] >= 0 and box["y"] + box["height"] <= page.viewport_size["height"]
            assert page.evaluate(f"document.elementFromPoint({box['x'] + box['width'] / 2}, "
                                 f"{box['y'] + box['height'] / 2}).id") == "busy"
            page.evaluate("trame.state.set('trame__busy', 0)")
            page.wait_for_function(f"!({BUSY_VISIBLE})", timeout=5000)
