"""The studio's incremental 3D scene and check, in-process: an edit rebuilds only the parts it
changed, and the result is the from-scratch scene and the library check, array for array and
violation for violation; the view's actors follow the scene and show the check's verdicts."""
import numpy as np
import pytest

from stitchswitch.errors import InvalidInputError
from stitchswitch.layout.check.constraints import CheckLimits, check_design
from stitchswitch.layout.check.small_pieces import small_piece_warnings
from stitchswitch.layout.garment.design import Design, MachineSpec, MaterialRef, PatchSpec
from stitchswitch.layout.garment.piece_select import rectangle_piece
from stitchswitch.preview3d import colours
from stitchswitch.preview3d.scene import SceneBuilder, build_scene
from stitchswitch.preview3d.spec import spec_from_design
from stitchswitch.studio.live_check import LiveCheck
from stitchswitch.studio.state import StudioState
from stitchswitch.studio.view3d.scene3d import PlotterSync, Scene3D, group_of, view_scale


def grid_design(n=3, m=2, pieces=1):
    """n x m patches on each of ``pieces`` 400 x 300 mm panels (the second one 500 mm to the
    right), d 30..55 mm, fill 0.6..0.9, every third patch down."""
    out, patches = [], []
    for k in range(pieces):
        piece = rectangle_piece(400.0, 300.0, f"panel{k}")
        out.append(piece.__class__(piece.name, piece.size, piece.source,
                                   piece.outline_mm + np.array([500.0 * k, 0.0])))
        for i in range(n):
            for j in range(m):
                idx = len(patches)
                patches.append(PatchSpec(f"p{idx}", f"panel{k}", (500.0 * k + 60.0 + 90.0 * i,
                                                                  70.0 + 100.0 * j),
                                         30.0 + 5.0 * ((i + j) % 6), 0.6 + 0.1 * ((i * j) % 4),
                                         state="down" if idx % 3 == 0 else "up"))
    return Design(1, tuple(out), tuple(patches), MaterialRef("default"), MachineSpec())


def same_scene(a, b):
    pa, ta, da = a.merged()
    pb, tb, db = b.merged()
    assert np.array_equal(pa, pb) and np.array_equal(ta, tb)
    assert np.array_equal(da["patch_index"], db["patch_index"])
    assert [ln.name for ln in a.lines] == [ln.name for ln in b.lines]
    assert all(np.array_equal(x.points, y.points) for x, y in zip(a.lines, b.lines))


def same_check(a, b):
    """Violation lists equal field by field (repr: a NaN value equals itself)."""
    assert [repr(v) for v in a] == [repr(v) for v in b]


def edits(state):
    """A sequence of edits of every kind, yielding after each."""
    first, second = state.design.patches[0].id, state.design.patches[1].id
    for change in ({"fill": 0.75}, {"fill": 0.8}, {"diameter_mm": 50.0}, {"state": "up"}):
        state.edit_patch(first, own_step=True, **change)
        yield
    x, y = state.design.patch(second).centre_mm
    state.move_patch(second, (x + 25.0, y + 10.0))           # closer to a neighbour: rims shared
    yield
    state.move_patch(second, (15.0, y))                      # over the piece edge
    yield
    state.add_patch((200.0, 150.0), diameter_mm=40.0, fill=0.9)
    yield
    state.remove_patch(first)
    yield
    state.undo()
    yield
    state.edit_patch(second, own_step=True, fill=0.06)       # a feature-size violation
    yield


@pytest.mark.parametrize("pieces, resolution", [(1, (64, 1)), (2, (64, 1)), (1, (32, 2))])
def test_incremental_scene_is_the_scene_built_from_scratch(pieces, resolution):
    s = StudioState(grid_design(pieces=pieces))
    builder = SceneBuilder(*resolution)

    def scratch():
        return SceneBuilder(*resolution).build(spec_from_design(s.design))

    same_scene(builder.build(spec_from_design(s.design)), scratch())
    if resolution == (64, 1):
        same_scene(scratch(), build_scene(spec_from_design(s.design)))
    for _ in edits(s):
        same_scene(builder.build(spec_from_design(s.design)), scratch())


def test_the_lighter_view_keeps_the_apex_footprint_and_blend():
    full = SceneBuilder().build(spec_from_design(grid_design()))
    light = SceneBuilder(32, 2).build(spec_from_design(grid_design()))
    for a, b in zip(full.patches, light.patches):
        assert b.height_mm == a.height_mm
        assert b.profile.boundary_radius_mm == a.profile.boundary_radius_mm
        assert b.surface.blend_start_mm == a.surface.blend_start_mm
        assert b.surface.rim_radius_mm == a.surface.rim_radius_mm
        assert len(b.surface.triangles) <= 0.3 * len(a.surface.triangles)
    with pytest.raises(InvalidInputError, match="ring_step"):
        SceneBuilder(32, 0)


def test_an_edit_rebuilds_only_what_it_changed():
    s = StudioState(grid_design(n=4, m=2, pieces=2))
    builder = SceneBuilder()
    before = builder.build(spec_from_design(s.design))
    s.edit_patch("p3", fill=0.9)                # the far corner of panel0: no rim changes
    after = builder.build(spec_from_design(s.design))
    rebuilt = [p.id for p, q in zip(before.patches, after.patches) if p is not q]
    assert rebuilt == ["p3"]
    assert all(a is b for a, b in zip(before.pieces, after.pieces))          # no hole moved
    assert [a is b for a, b in zip(before.lines, after.lines)].count(False) == 1
    s.move_patch("p9", (s.design.patch("p9").centre_mm[0] + 3.0, 170.0))     # on panel1
    moved = builder.build(spec_from_design(s.design))
    assert moved.pieces[0] is after.pieces[0] and moved.pieces[1] is not after.pieces[1]
    assert {p.id for p, q in zip(after.patches, moved.patches) if p is not q} >= {"p9"}


@pytest.mark.parametrize("pieces", [1, 2])
def test_incremental_check_is_the_library_check(pieces):
    s = StudioState(grid_design(pieces=pieces))
    live = LiveCheck()
    same_check(live.run(s.design), check_design(s.design))
    assert live.rechecked == len(s.design.patches)
    seen = set()
    for _ in edits(s):
        got = live.run(s.design)
        same_check(got, check_design(s.design))
        assert live.rechecked <= 2
        seen |= {v.rule for v in got}
    assert {"piece-edge", "feature-side"} <= seen            # the edits did break rules


def test_incremental_small_pieces_are_the_library_warnings():
    s = StudioState(grid_design())
    live = LiveCheck()
    live.run(s.design)
    assert live.small == small_piece_warnings(s.design, CheckLimits())
    seen = {tuple(w.patch for w in live.small)}
    for d, fill in ((80.0, 0.3), (80.0, 0.9), (30.0, 0.7), (40.0, 0.3)):
        s.edit_patch("p1", diameter_mm=d, fill=fill)
        live.run(s.design)
        assert live.small == small_piece_warnings(s.design, CheckLimits())
        assert live.rechecked == 1
        seen.add(tuple((w.patch, w.count) for w in live.small))
    for _ in edits(s):
        live.run(s.design)
        assert live.small == small_piece_warnings(s.design, CheckLimits())
    assert len(seen) >= 3                        # the warnings did change with the edits


def test_view_actors_follow_the_scene_and_show_the_check():
    pv = pytest.importorskip("pyvista")
    pv.OFF_SCREEN = True
    s = StudioState(grid_design())
    scene3d = Scene3D()
    scene3d.update(s.design)
    pl = pv.Plotter(off_screen=True)
    try:
        sync = PlotterSync(pl)
        groups = {group_of(p.id) for p in s.design.patches}
        assert sync.sync(scene3d)["added"] == 1 + len(groups) + 2   # piece, patch groups, outlines
        s.edit_patch("p5", fill=0.9)
        scene3d.update(s.design)
        counts = sync.sync(scene3d)
        assert counts["rebuilt"] == 2 and counts["added"] == counts["removed"] == 0   # surface, lines
        name = f"patches:{group_of('p5')}"
        content, actor, mesh = sync.actors[name]
        assert [p.id for p in content] == [p.id for p in s.design.patches
                                           if group_of(p.id) == group_of("p5")]
        z = np.concatenate([p.surface.points[:, 2] for p in content])
        assert np.array_equal(mesh.point_data["height (mm)"], z.astype(np.float32))
        # the view's arrays are float32, what WebGL draws with (half the bytes to send)
        assert mesh.points.dtype == mesh.point_data["height (mm)"].dtype == np.float32
        assert sync.actors["lines:patch:ok"][2].points.dtype == np.float32
        assert scene3d.scene.patches[5] in content                  # the rebuilt surface is shown
        assert tuple(actor.mapper.scalar_range) == scene3d.clim
        s.move_patch("p1", (10.0, 70.0))                         # over the edge: an error
        scene3d.update(s.design)
        violations = check_design(s.design)
        sync.sync(scene3d, violations)
        flagged = sync.actors["lines:patch:error"]
        assert [ln.name for ln in flagged[0]] == ["p1"]
        red = np.array(colours.STATUS_RGB["error"]) / 255.0
        assert np.allclose(flagged[1].prop.color.float_rgb, red, atol=1 / 255)
        assert flagged[1].prop.line_width > sync.actors["lines:patch:ok"][1].prop.line_width
        assert "p1" not in [ln.name for ln in sync.actors["lines:patch:ok"][0]]
        s.remove_patch("p4")
        scene3d.update(s.design)
        sync.sync(scene3d, violations)
        assert "p4" not in [p.id for name, (c, _, _) in sync.actors.items()
                            if name.startswith("patches:") for p in c]
        s.undo()                                                 # p4 back
        s.undo()                                                 # p1 back in place
        scene3d.update(s.design)
        sync.sync(scene3d, check_design(s.design))
        assert "lines:patch:error" not in sync.actors
    finally:
        pl.close()


@pytest.mark.parametrize("heights", [[3.0, 10.0], [-4.0, 8.0], [-6.0, -2.0], [5.0]])
def test_view_colour_range_is_the_heights_range_with_the_canvas_colours(heights):
    """The 3D view's colour range is the heights' own (with the flat fabric's 0), and each
    height gets the colour of the canvas's symmetric map (coolwarm over -H..H)."""
    pv = pytest.importorskip("pyvista")
    from matplotlib import colormaps

    from stitchswitch.studio.view3d.scene3d import _lookup_table

    (a, b), (lo, hi) = view_scale(heights)
    assert (lo, hi) == (min(0.0, *heights), max(0.0, *heights))
    lut = _lookup_table(pv, (a, b))
    lut.scalar_range = (lo, hi)
    big = max(abs(h) for h in heights)
    for h in [*heights, 0.0]:
        rgb = [0.0, 0.0, 0.0]
        lut.GetColor(h, rgb)
        assert np.allclose(rgb, colormaps[colours.HEIGHT_CMAP](0.5 + 0.5 * h / big)[:3], atol=0.02)
