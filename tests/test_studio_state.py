"""The studio's state and actions in-process, without a browser: add, move, edit, remove,
undo / redo, the live readout, the check, inverse apply, save (byte-identical when unchanged),
autosave, grouping and export."""
import json
import os
import re

import numpy as np
import pytest

from stitchswitch.errors import InvalidInputError
from stitchswitch.layout.check.constraints import check_design
from stitchswitch.layout.garment.design import Design, MachineSpec, MaterialRef
from stitchswitch.layout.garment.design_io import load_design, save_design
from stitchswitch.layout.garment.piece_select import rectangle_piece
from stitchswitch.reduced.design_space.cache import default_map
from stitchswitch.reduced.design_space.inverse import InverseTarget
from stitchswitch.studio import fabrication, inverse_panel, live_check
from stitchswitch.studio.persist import Document, sidecar_path
from stitchswitch.studio.readout import heights_mm, profile_svg, readout
from stitchswitch.studio.session import Session
from stitchswitch.studio.state import StudioState

from decoders import jef


@pytest.fixture
def empty():
    return Design(1, (rectangle_piece(400.0, 300.0, "panel"),), (), MaterialRef("default"), MachineSpec())


@pytest.fixture
def design_file(tmp_path, empty):
    path = tmp_path / "d.json"
    save_design(empty, path)
    return path


def centre(design):
    o = design.pieces[0].outline_mm
    return tuple(o.mean(axis=0))


def test_add_move_edit_remove_undo_redo(empty):
    s = StudioState(empty)
    c = centre(empty)
    pid = s.add_patch(c)
    assert s.selected == pid and [p.id for p in s.design.patches] == [pid]
    assert s.design.patch(pid).piece == "panel"
    s.move_patch(pid, (c[0] + 20, c[1]))
    assert s.design.patch(pid).centre_mm == (c[0] + 20, c[1])
    for f in (0.6, 0.65, 0.7):                       # a dragged slider: one undo step
        s.edit_patch(pid, fill=f)
    assert s.design.patch(pid).fill == 0.7
    s.undo()
    assert s.design.patch(pid).fill == 0.5 and s.design.patch(pid).centre_mm == (c[0] + 20, c[1])
    s.redo()
    assert s.design.patch(pid).fill == 0.7
    s.remove_patch(pid)
    assert s.design.patches == () and s.selected is None
    for _ in range(4):
        s.undo()
    assert s.design == empty and not s.can_undo
    s.redo()
    assert len(s.design.patches) == 1


def test_bad_actions_are_clear_errors(empty):
    s = StudioState(empty)
    with pytest.raises(InvalidInputError, match="not on a piece"):
        s.add_patch((5000.0, 5000.0))
    pid = s.add_patch(centre(empty))
    with pytest.raises(InvalidInputError, match="fill"):
        s.edit_patch(pid, fill=1.5)
    with pytest.raises(InvalidInputError, match="not an editable"):
        s.edit_patch(pid, id="x")
    assert s.design.patch(pid).fill == 0.5             # a refused edit changes nothing


def test_hit_testing(empty):
    s = StudioState(empty)
    c = centre(empty)
    pid = s.add_patch(c, diameter_mm=60.0)
    eta = empty.material_object().eta
    assert s.patch_at((c[0] + 0.9 * 30 / eta, c[1])) == pid
    assert s.patch_at((c[0] + 1.1 * 30 / eta, c[1])) is None


def test_readout_follows_the_map():
    dmap = default_map()
    a, b = readout(dmap, 60.0, 0.4), readout(dmap, 60.0, 0.8)
    q = dmap.query(60.0, 0.8)
    assert b.in_domain and b.keypoints_mm["h_mm"] == pytest.approx(float(q.h_mm[0]))
    assert a.keypoints_mm["h_mm"] != b.keypoints_mm["h_mm"]
    assert b.force_N > 0 and b.r_mm.shape == b.z_mm.shape
    design = Design(1, (rectangle_piece(400.0, 300.0, "panel"),), (), MaterialRef("default"), MachineSpec())
    s = StudioState(design)
    pid = s.add_patch((200.0, 150.0), diameter_mm=60.0, fill=0.8)
    assert heights_mm(dmap, s.design) == {pid: b.keypoints_mm["h_mm"]}
    svg = profile_svg(b.r_mm, b.z_mm)
    pts = np.array([[float(v) for v in p.split(",")]
                    for p in re.search(r'data-profile="1" points="([^"]+)"', svg).group(1).split()])
    assert -pts[:, 1].min() == pytest.approx(float(b.z_mm.max()), abs=0.01)     # the apex
    assert pts[:, 0].max() == pytest.approx(float(b.r_mm.max()), abs=0.01)
    assert profile_svg(None, None) == ""
    out = readout(dmap, 1000.0, 0.5)
    assert not out.in_domain and "outside the map's domain" in out.message


@pytest.mark.parametrize("d, fill", [(60.0, 0.8), (30.0, 0.6), (90.0, 0.5)])
def test_the_plotted_profile_is_the_profile_to_a_quarter_pixel(d, fill):
    """The plot's polyline drops nodes, none of the profile's nodes (or their mirror images) is
    further than a quarter of the plot's pixel from it (and the SVG's 0.01 mm rounding)."""
    from shapely.geometry import LineString, Point

    from stitchswitch.studio.readout import HEIGHT_PX, WIDTH_PX

    r = readout(default_map(), d, fill)
    svg = profile_svg(r.r_mm, r.z_mm)
    view = [float(v) for v in re.search(r'viewBox="([^"]+)"', svg).group(1).split()]
    mm_per_px = max(view[2] / WIDTH_PX, view[3] / HEIGHT_PX)
    pts = np.array([[float(v) for v in p.split(",")]
                    for p in re.search(r'data-profile="1" points="([^"]+)"', svg).group(1).split()])
    assert len(pts) < len(r.r_mm)
    line = LineString(pts)
    far = max(line.distance(Point(sx * a, -b)) for a, b in zip(r.r_mm, r.z_mm) for sx in (1, -1))
    assert far <= 0.25 * mm_per_px + 0.01


def test_check_is_the_library_check(empty):
    s = StudioState(empty)
    pid = s.add_patch(centre(empty))
    assert live_check.run_check(s.design) == check_design(s.design)
    assert live_check.errors(live_check.run_check(s.design)) == 0
    o = empty.pieces[0].outline_mm
    s.move_patch(pid, (o[:, 0].min() + 3.0, centre(empty)[1]))      # over the piece edge
    v = live_check.run_check(s.design)
    assert live_check.patch_status(v).get(pid) == "error"
    assert any(r["rule"] == "piece-edge" for r in live_check.rows(v))
    s.undo()
    assert live_check.errors(live_check.run_check(s.design)) == 0


def test_inverse_apply(empty):
    s = StudioState(empty)
    pid = s.add_patch(centre(empty))
    cands = inverse_panel.candidates(InverseTarget(height_mm=12.0, count=2), default_map(), s)
    assert cands and all(c.check_errors == 0 for c in cands)
    inverse_panel.apply(s, cands[0].candidate)
    p = s.design.patch(pid)
    assert p.diameter_mm == pytest.approx(cands[0].candidate.diameter_mm, abs=1e-6)
    assert readout(default_map(), p.diameter_mm, p.fill).keypoints_mm["h_mm"] == pytest.approx(12.0, abs=0.3)
    s.undo()
    assert s.design.patch(pid).diameter_mm == 60.0


def test_save_unchanged_is_byte_identical(tmp_path, design_file):
    raw = design_file.read_bytes()
    noncanonical = json.dumps(json.loads(raw))            # valid, but not the canonical text
    design_file.write_text(noncanonical)
    doc, design = Document.open(design_file)
    s = StudioState(design)
    pid = s.add_patch(centre(design))
    s.remove_patch(pid)
    assert not doc.dirty(s.design)
    doc.save(s.design)
    assert design_file.read_text() == noncanonical
    s.add_patch(centre(design))
    assert doc.dirty(s.design)
    doc.save(s.design)
    assert load_design(design_file) == s.design and design_file.read_bytes() != noncanonical.encode()


def test_autosave_sidecar(design_file):
    doc, design = Document.open(design_file)
    s = StudioState(design)
    s.add_patch(centre(design))
    doc.autosave(s.design)
    assert os.path.exists(sidecar_path(design_file))
    again, _ = Document.open(design_file)
    assert again.recover() == s.design
    doc.save(s.design)
    assert not os.path.exists(sidecar_path(design_file)) and again.recover() is None


def test_grouping_and_export(tmp_path, design_file):
    doc, design = Document.open(design_file)
    s = StudioState(design)
    c = centre(design)
    s.add_patch((c[0] - 40, c[1]), diameter_mm=50.0)
    s.add_patch((c[0] + 40, c[1]), diameter_mm=50.0)
    grouping, order = fabrication.hoopings(s.design)
    assert sorted(i for h in order.hoopings for i in h.patch_ids) == sorted(p.id for p in s.design.patches)
    doc.save(s.design)
    result = fabrication.export(s.design, tmp_path / "out")
    jefs = [f for f in result.files if f.endswith(".jef")]
    assert len(jefs) == len(order.hoopings)
    for name, h in zip(sorted(jefs), result.order.hoopings):
        decoded = jef.decode((tmp_path / "out" / name).read_bytes())
        xy = np.array([(x, y) for kind, x, y in decoded.records if kind == "stitch"]) / 10.0
        expected = np.ptp(np.array(h.positions_mm), axis=0) + 50.0     # centres' span + d
        assert np.ptp(xy, axis=0) == pytest.approx(expected, abs=2.0)


def test_grouping_uses_fabricates_hoop_choice(design_file):
    from stitchswitch.layout.fabrication.fabricate import FabricateOptions, grouping_hoops

    doc, design = Document.open(design_file)
    s = StudioState(design)
    c = centre(design)
    s.add_patch((c[0] - 40, c[1]), diameter_mm=50.0)
    s.add_patch((c[0] + 40, c[1]), diameter_mm=50.0)
    every = {h.name for h in grouping_hoops(s.design)}
    assert len(every) > 1
    one = FabricateOptions(hoop="SQ20b")
    assert [h.name for h in grouping_hoops(s.design, one)] == ["SQ20b"]
    _, order = fabrication.hoopings(s.design, one)
    assert {h.hoop.name for h in order.hoopings} == {"SQ20b"}
    _, order = fabrication.hoopings(s.design)
    assert {h.hoop.name for h in order.hoopings} <= every


def test_multi_select_moves_and_removes_together(empty):
    s = StudioState(empty)
    c = centre(empty)
    a = s.add_patch((c[0] - 60, c[1]))
    b = s.add_patch((c[0] + 60, c[1]))
    d = s.add_patch((c[0], c[1] + 80))
    s.select(a)
    s.toggle_select(b)
    assert s.selection == (a, b) and s.selected == b          # the inspector shows the last
    s.move_patches(s.selection, 10.0, -5.0)
    assert s.design.patch(a).centre_mm == (c[0] - 50, c[1] - 5)
    assert s.design.patch(b).centre_mm == (c[0] + 70, c[1] - 5)
    assert s.design.patch(d).centre_mm == (c[0], c[1] + 80)
    s.undo()                                                   # one step for both
    assert s.design.patch(a).centre_mm == (c[0] - 60, c[1]) and s.selection == (a, b)
    s.toggle_select(a)
    assert s.selection == (b,)
    s.toggle_select(d)
    s.remove_patches(s.selection)
    assert [p.id for p in s.design.patches] == [a] and s.selection == ()
    s.undo()
    assert len(s.design.patches) == 3 and s.selection == (b, d)
    s.select(a)
    assert s.selection == (a,)


def test_composite_and_conductive_options(tmp_path, design_file):
    doc, design = Document.open(design_file)
    session = Session(doc, design, default_map())
    pid = session.add(centre(design))
    session.set_composite(20.0, 0.9)
    p = session.state.design.patch(pid)
    assert p.composite.core_diameter_mm == 20.0 and p.composite.core_fill == 0.9
    session.set_conductive("ring:0")
    assert session.state.design.patch(pid).conductive == "ring:0"
    with pytest.raises(InvalidInputError, match="selection"):
        session.set_conductive("spiral:3")
    with pytest.raises(InvalidInputError, match="core_diameter_mm"):
        session.set_composite(200.0, 0.9)                      # larger than the patch
    assert session.state.design.patch(pid).composite.core_diameter_mm == 20.0
    session.save()
    saved = load_design(design_file).patch(pid)
    assert saved.composite == p.composite and saved.conductive == "ring:0"
    session.set_composite(None)
    session.set_conductive("")
    p = session.state.design.patch(pid)
    assert p.composite is None and p.conductive is None
    session.undo()
    assert session.state.design.patch(pid).conductive == "ring:0"


def test_canvas_zoom_pan_rulers_and_drag_guides(design_file):
    from stitchswitch.studio import canvas

    doc, design = Document.open(design_file)
    session = Session(doc, design, default_map())
    fit = session.view()
    w_px, h_px = 800.0, 600.0
    about = canvas.to_mm(fit, 300.0, 200.0, w_px, h_px)
    session.zoom(2.0, about)
    v = session.view()
    assert v.width == pytest.approx(fit.width / 2)
    assert canvas.to_mm(v, 300.0, 200.0, w_px, h_px) == pytest.approx(about)   # stays put
    for _ in range(40):
        session.zoom(2.0)
    assert session.view().width == pytest.approx(fit.width * canvas.ZOOM_RANGE[0])
    session.fit_view()
    session.pan(30.0, -20.0)
    v = session.view()
    x, y = canvas.to_mm(fit, 300.0, 200.0, w_px, h_px)
    assert canvas.to_mm(v, 300.0, 200.0, w_px, h_px) == pytest.approx((x - 30.0, y + 20.0))
    svg = session.canvas_svg()
    assert f'viewBox="{v.x0:.2f} {v.y0:.2f}' in svg
    xs = [float(t) for t in re.findall(r'data-ruler-x="([-\d.]+)"', svg)]
    assert xs and np.allclose(np.diff(xs), 50.0)             # a 50 mm ruler step on 400 mm
    ys = [float(t) for t in re.findall(r'data-ruler-y="([-\d.]+)"', svg)]
    assert ys and 0.0 in ys and 300.0 in ys
    pid = session.add(centre(design))
    assert "data-guide" not in session.canvas_svg()
    session.dragging = (pid,)
    svg = session.canvas_svg()
    ring = np.array([[float(c) for c in pt.split(",")] for pt in re.search(
        r'points="([^"]+)"[^>]*data-guide="centre"', svg).group(1).split()])
    eta = design.material_object().eta
    inset = 10.0 + 5.0 + 60.0 / (2 * eta)                      # seam + clearance + radius
    assert ring[:, 0].min() == pytest.approx(inset, abs=0.05)
    assert -ring[:, 1].max() == pytest.approx(inset, abs=0.05)  # y negated in the SVG
    assert 'data-guide="seam"' in svg


def test_dragged_patches_follow_the_pointer_with_their_edge_rule(tmp_path):
    """While dragged, the canvas draws the patches where the pointer is, on the piece under
    the new centre with that piece's edge rule; the design changes only on release."""
    a = rectangle_piece(400.0, 300.0, "a")
    b = a.__class__("b", a.size, a.source, a.outline_mm + np.array([500.0, 0.0]))
    design = Design(1, (a, b), (), MaterialRef("default"), MachineSpec(), path=str(tmp_path / "d.json"))
    session = Session(Document(design.path, design), design, default_map())
    pid = session.add((200.0, 150.0))
    before, edits = session.state.design, session.state.changed

    def circle(svg):
        m = re.search(rf'<circle data-patch="{pid}" cx="([-\d.]+)" cy="([-\d.]+)"', svg)
        return float(m.group(1)), -float(m.group(2))

    def centre_rule_x(svg):
        ring = re.search(r'points="([^"]+)"[^>]*data-guide="centre"', svg).group(1).split()
        return min(float(pt.split(",")[0]) for pt in ring)

    session.drag_to(100.0, 0.0)                      # no patch held: nothing follows
    assert circle(session.canvas_svg()) == (200.0, 150.0)
    session.dragging = (pid,)
    session.drag_to(30.0, -20.0)
    svg = session.canvas_svg()
    assert circle(svg) == pytest.approx((230.0, 130.0))
    inset = 10.0 + 5.0 + 60.0 / (2 * design.material_object().eta)
    assert centre_rule_x(svg) == pytest.approx(inset, abs=0.05)       # piece a's rule
    session.drag_to(400.0, 0.0)                                       # over piece b
    svg = session.canvas_svg()
    assert circle(svg) == pytest.approx((600.0, 150.0))
    assert centre_rule_x(svg) == pytest.approx(500.0 + inset, abs=0.05)   # piece b's rule
    # the page draws the canvas in three layers, and a drag redraws only the patches' one
    pieces, patches, rulers = session.canvas_layers()
    assert session.canvas_patches() == patches
    assert circle(patches) == pytest.approx((600.0, 150.0))
    assert centre_rule_x(patches) == pytest.approx(500.0 + inset, abs=0.05)
    inner = [re.sub(r"^<svg[^>]*>|</svg>$", "", layer) for layer in (pieces, patches, rulers)]
    assert re.sub(r"^<svg[^>]*>|</svg>$", "", svg) == "".join(inner)   # the single SVG's markup
    assert session.state.design is before and session.state.changed == edits   # not an edit
    session.end_drag()
    session.move(pid, (600.0, 150.0))                                 # the release
    assert session.state.design.patch(pid).piece == "b"
    assert circle(session.canvas_svg()) == (600.0, 150.0) and "data-guide" not in session.canvas_svg()


def test_stitch_plan_preview_and_downloads(tmp_path, design_file):
    doc, design = Document.open(design_file)
    session = Session(doc, design, default_map())
    c = centre(design)
    session.add((c[0] - 40, c[1]))
    session.add((c[0] + 40, c[1]))
    with pytest.raises(InvalidInputError, match="group"):
        session.plan_preview(0)
    session.group("garment")
    svg, n = session.plan_preview(0)
    runs = [np.array([[float(v) for v in pt.split(",")] for pt in m.split()])
            for m in re.findall(r'<polyline data-run="\d+" points="([^"]+)"', svg)]
    assert runs and n["stitches"] > 100 and n["minutes"] > 0
    shown = np.vstack(runs) * [1.0, -1.0]                       # back to hoop mm, y up
    with pytest.raises(InvalidInputError, match="hooping 9"):
        session.plan_preview(8)
    session.save()
    result = session.export(tmp_path / "out")
    first = result.doc.as_dict()["hoopings"][0]                # stitched first
    jef_bytes = session.exported_file(first["files"]["embroidery"])
    assert jef_bytes == (tmp_path / "out" / first["files"]["embroidery"]).read_bytes()
    xy = np.array([(x, y) for kind, x, y in jef.decode(jef_bytes).records if kind == "stitch"]) / 10.0
    # the preview is the machine file's plan: the same stitch extent (0.1 mm units in the file)
    assert np.ptp(shown, axis=0) == pytest.approx(np.ptp(xy, axis=0), abs=0.3)
    with pytest.raises(InvalidInputError, match="not a file of the last export"):
        session.exported_file("../d.json")


def test_size_picker_puts_the_design_on_another_size(tmp_path):
    from pathlib import Path

    from stitchswitch.layout.garment.dxf.reader import import_dxf
    from stitchswitch.layout.garment.piece_select import select_pieces

    tank = Path(__file__).parent / "data/external/dxf/WM_LOOSE_SHAPE_TANK_AAMA.DXF"
    pattern = import_dxf(tank)
    start = Design(1, select_pieces(pattern, "26"), (), MaterialRef("default"), MachineSpec(),
                   path=str(tmp_path / "tank.json"))
    session = Session(Document(start.path, start), start, default_map(), pattern=pattern)
    assert session.sizes[:2] == ["26", "28"] and len(session.sizes) == 14 and session.size == "26"
    front = session.state.design.pieces[0]
    pid = session.add(tuple(front.outline_mm.mean(axis=0)))
    where = session.state.design.patch(pid).centre_mm
    session.set_size("36")
    d = session.state.design
    assert session.size == "36" and [p.name for p in d.pieces] == [p.name for p in start.pieces]
    assert np.allclose(d.pieces[0].outline_mm, select_pieces(pattern, "36")[0].outline_mm, atol=1e-6)
    assert d.patch(pid).centre_mm == where                     # the patch stays where it was
    assert [repr(v) for v in session.violations] == [repr(v) for v in check_design(d)]
    session.undo()
    assert session.size == "26" and len(session.state.design.patches) == 1
    with pytest.raises(InvalidInputError, match="XL"):
        session.set_size("XL")
    bare = Session(Document(start.path, start), start, default_map())
    assert bare.sizes == []
    with pytest.raises(InvalidInputError, match="graded pattern"):
        bare.set_size("36")


def test_a_reopened_design_offers_its_patterns_sizes(tmp_path):
    """A design started in the studio from a graded pattern names the pattern relative to the
    design file; reopened (the pattern in another folder), it offers the pattern's sizes, and
    saved without changes it is byte-identical and passes ``stitchswitch check``. A design
    whose pieces name the pattern by file name (as ``import`` writes) finds it beside itself; a
    missing pattern gives a note and no size picker."""
    import shutil
    from pathlib import Path

    from click.testing import CliRunner

    from stitchswitch.cli.main import cli
    from stitchswitch.cli.studio import _source
    from stitchswitch.layout.garment.piece_select import select_pieces
    from stitchswitch.studio.persist import source_pattern

    (tmp_path / "patterns").mkdir()
    (tmp_path / "designs").mkdir()
    tank = tmp_path / "patterns" / "tank.dxf"
    shutil.copy(Path(__file__).parent / "data/external/dxf/WM_LOOSE_SHAPE_TANK_AAMA.DXF", tank)
    out = tmp_path / "designs" / "tank.json"
    document, design, pattern = _source(str(tank), None, str(out), "30")
    assert {p.source for p in design.pieces} == {os.path.join("..", "patterns", "tank.dxf")}
    session = Session(document, design, default_map(), pattern=pattern)
    session.add(tuple(design.pieces[0].outline_mm.mean(axis=0)))
    session.save()
    saved = out.read_bytes()
    document, design, pattern = _source(str(out), None, None)        # reopened
    assert pattern is not None
    reopened = Session(document, design, default_map(), pattern=pattern)
    assert len(reopened.sizes) == 14 and reopened.size == "30"
    reopened.save()                                                  # no change: same bytes
    assert out.read_bytes() == saved
    result = CliRunner().invoke(cli, ["check", str(out)])
    assert result.exit_code in (0, 1) and "Error:" not in result.output, result.output
    reopened.set_size("36")
    assert reopened.size == "36" and reopened.state.design.pieces[0].source == design.pieces[0].source
    # the file name only, as `stitchswitch import` records it: looked up beside the design
    beside = Design(1, select_pieces(pattern, "26"), (), MaterialRef("default"), MachineSpec())
    assert {p.source for p in beside.pieces} == {"tank.dxf"}
    found, note = source_pattern(beside, tmp_path / "patterns" / "beside.json")
    assert found is not None and note == ""
    found, note = source_pattern(beside, tmp_path / "designs" / "elsewhere.json")
    assert found is None and "'tank.dxf'" in note and "no size picker" in note
    rect = Design(1, (rectangle_piece(400.0, 300.0),), (), MaterialRef("default"), MachineSpec())
    assert source_pattern(rect, out) == (None, "")


def test_deferred_autosave(design_file):
    doc, design = Document.open(design_file)
    session = Session(doc, design, default_map())
    session.autosave_later = True
    session.add(centre(design))
    assert not os.path.exists(sidecar_path(design_file))      # left to the page, right after
    session.write_autosave()
    assert Document.open(design_file)[0].recover() == session.state.design
    session.autosave_later = False
    session.undo()
    assert Document.open(design_file)[0].recover() == session.state.design


def test_inverse_candidate_placed_where_clicked(design_file):
    doc, design = Document.open(design_file)
    session = Session(doc, design, default_map())
    cands = session.run_inverse(InverseTarget(height_mm=12.0, count=2))
    assert cands and session.state.selected is None
    c = centre(design)
    pid = session.apply_candidate(0, (c[0] + 50.0, c[1]))
    p = session.state.design.patch(pid)
    assert p.centre_mm == (c[0] + 50.0, c[1]) and session.state.selected == pid
    assert p.diameter_mm == pytest.approx(cands[0].candidate.diameter_mm, abs=1e-6)
    with pytest.raises(InvalidInputError, match="candidate 9"):
        session.apply_candidate(8)
    session.undo()
    assert session.state.design.patches == ()
