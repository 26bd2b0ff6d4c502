"""The 3D preview: blend, placement, fabric, offscreen rendering, mesh export, single view."""
import matplotlib
import meshio
import numpy as np
import pytest

from stitchswitch import InvalidInputError, Patch, solve
from stitchswitch.preview3d import colours, fabric, mesh_io, render, single, surfaces
from stitchswitch.preview3d.camera import fit_camera, frame_points, world_to_pixel
from stitchswitch.preview3d.profiles import patch_profiles, single_profile
from stitchswitch.preview3d.scene import build_scene
from stitchswitch.preview3d.spec import PreviewPatch, PreviewPiece, PreviewSpec

SIZE = (320, 240)


def small_spec(states=("up", "up", "down")):
    """A 200 x 120 mm piece with three patches on the map's grid (d, fill exact grid points)."""
    piece = PreviewPiece("front", np.array([[0, 0], [200, 0], [200, 120], [0, 120]], float))
    patches = (PreviewPatch("big", (50.0, 60.0), 60.0, 1.0, states[0]),
               PreviewPatch("small", (110.0, 60.0), 40.0, 0.8, states[1]),
               PreviewPatch("down", (160.0, 60.0), 40.0, 0.8, states[2]))
    return PreviewSpec((piece,), patches)


@pytest.fixture(scope="module")
def scene():
    return build_scene(small_spec())


@pytest.fixture(scope="module")
def model_h():
    return {d: solve(Patch(d, p)).keypoints.h_mm for d, p in ((60.0, 1.0), (40.0, 0.8))}


def test_blend_keeps_the_dome_and_meets_the_flat_fabric_at_the_rim():
    prof = single_profile(40.0, 0.8)
    rim = surfaces.RIM * prof.boundary_radius_mm
    R, r, z = surfaces.shown_profile(prof, rim)
    r1 = surfaces.blend_start_mm(prof)
    dome = R <= r1
    assert np.array_equal(r[dome], prof.r_mm[: dome.sum()])        # untouched up to R_1
    assert np.array_equal(z[dome], prof.z_mm[: dome.sum()])
    assert R[-1] == rim and r[-1] == rim and z[-1] == 0.0           # flat at the rim, r = R
    assert np.all(np.diff(z) <= 1e-12)                              # still non-increasing
    assert r1 >= prof.R_mm[prof.keypoints.b_index]                  # keypoint b is kept


def test_rims_are_shared_between_close_neighbours():
    profs = patch_profiles([40.0, 60.0, 40.0], [0.8, 1.0, 0.8])
    rb = np.array([p.boundary_radius_mm for p in profs])
    far = surfaces.rim_radii_mm(np.array([[0, 0], [500, 0], [0, 500]]), profs)
    assert np.allclose(far, surfaces.RIM * rb)
    centres = np.array([[0.0, 0.0], [50.0, 0.0], [0.0, 200.0]])
    rims = surfaces.rim_radii_mm(centres, profs)
    assert rims[0] + rims[1] <= 50.0 + 1e-9                         # do not overlap
    assert rims[0] / rims[1] == pytest.approx(rb[0] / rb[1])        # shared in proportion
    assert rims[2] == pytest.approx(surfaces.RIM * rb[2])


def test_patch_heights_are_the_models_h(scene, model_h):
    by_id = {p.id: p for p in scene.patches}
    assert by_id["big"].surface.points[:, 2].max() == pytest.approx(model_h[60.0], abs=0.01)
    assert by_id["small"].surface.points[:, 2].max() == pytest.approx(model_h[40.0], abs=0.01)
    down = by_id["down"].surface.points[:, 2]
    assert down.min() == pytest.approx(-model_h[40.0], abs=0.01) and down.max() <= 1e-12
    apex = by_id["small"].surface.points[0]
    assert apex[:2] == pytest.approx([110.0, 60.0])                # placed at its centre


def test_fabric_has_the_rims_as_holes(scene):
    piece = scene.pieces[0]
    pts = piece.points
    assert np.all(pts[:, 2] == 0.0)
    tri = pts[piece.triangles]
    u, v = tri[:, 1, :2] - tri[:, 0, :2], tri[:, 2, :2] - tri[:, 0, :2]
    area = 0.5 * np.abs(u[:, 0] * v[:, 1] - u[:, 1] * v[:, 0]).sum()
    n = surfaces.N_THETA
    holes = sum(0.5 * n * p.surface.rim_radius_mm ** 2 * np.sin(2 * np.pi / n) for p in scene.patches)
    assert area == pytest.approx(200 * 120 - holes, rel=1e-9)
    keys = {tuple(x) for x in pts[:, :2]}
    for p in scene.patches:                                         # rims are shared vertices
        rim = p.surface.points[-n:, :2]
        assert all(tuple(x) in keys for x in rim)
    with pytest.raises(InvalidInputError, match="not a simple polygon"):
        fabric.piece_polygon("bow", np.array([[0, 0], [1, 1], [1, 0], [0, 1]], float))


def test_camera_fit_and_pixel_map():
    pts = np.array([[0.0, 0.0, 0.0], [100.0, 50.0, 0.0]])
    cam = fit_camera(pts, "top", (220, 110), usable=1.0, margin=1.0)
    assert cam.parallel_scale == pytest.approx(25.0)
    assert world_to_pixel(cam, (220, 110), pts) == pytest.approx(np.array([[0, 110], [220, 0]]))
    cam = fit_camera(pts, "top", (220, 110), usable=0.5, margin=1.0)   # room for a legend
    assert world_to_pixel(cam, (220, 110), pts) == pytest.approx(np.array([[0, 82.5], [110, 27.5]]))
    side = fit_camera(np.array([[0.0, 0.0, -5.0], [100.0, 0.0, 20.0]]), "side", (200, 100),
                      margin=1.0)
    assert world_to_pixel(side, (200, 100), [[0.0, 0.0, 20.0]])[0] == pytest.approx([0, 25])


def _cmap_rgb(value, clim):
    t = (value - clim[0]) / (clim[1] - clim[0])
    return np.array(matplotlib.colormaps[colours.HEIGHT_CMAP](t)[:3]) * 255


def test_top_view_shows_each_patch_in_its_colour_where_it_is(scene):
    opts = render.RenderOptions(view="top", size=SIZE, lighting=False, legend=False,
                                piece="front", annotate=False)
    image, camera = render.render_scene(scene, opts)
    assert image.shape == (SIZE[1], SIZE[0], 3)
    assert len(np.unique(image.reshape(-1, 3), axis=0)) > 50        # not blank
    assert camera == fit_camera(frame_points(scene, piece="front"), "top", SIZE, usable=1.0)
    clim = colours.height_clim(scene)
    for p in scene.patches:
        col, row = np.round(world_to_pixel(camera, SIZE, [[*p.surface.centre_mm, 0.0]])[0]).astype(int)
        patch = image[row - 1:row + 2, col - 1:col + 2].reshape(-1, 3).astype(float)
        expected = _cmap_rgb(p.height_mm, clim)
        assert np.abs(patch - expected).max() < 12, (p.id, patch.mean(axis=0), expected)
    col, row = np.round(world_to_pixel(camera, SIZE, [[80.0, 15.0, 0.0]])[0]).astype(int)
    assert np.abs(image[row, col] - _cmap_rgb(0.0, clim)).max() < 12   # flat fabric: mid grey
    assert np.all(image[2, 2] == 255)                                # background above the piece


def test_lit_iso_render_is_deterministic_and_coloured(tmp_path, scene):
    opts = render.RenderOptions(view="iso", size=SIZE)
    a, b = tmp_path / "a.png", tmp_path / "b.png"
    render.render_to_png(a, scene, opts)
    render.render_to_png(b, scene, opts)
    assert a.read_bytes() == b.read_bytes() and a.read_bytes().startswith(b"\x89PNG")
    img = np.asarray(__import__("PIL.Image", fromlist=["Image"]).open(a))
    assert img.shape == (SIZE[1], SIZE[0], 3)
    red = (img[..., 0].astype(int) - img[..., 2] > 60).sum()
    blue = (img[..., 2].astype(int) - img[..., 0] > 60).sum()
    assert red > 500 and blue > 100                                  # up and down patches seen


@pytest.mark.parametrize("ext", [".vtu", ".ply", ".obj"])
def test_exported_mesh_rereads_with_the_models_height(tmp_path, scene, model_h, ext):
    path = tmp_path / f"design{ext}"
    n = mesh_io.write_scene_mesh(path, scene)
    points, tris, _ = scene.merged()
    expected = len(scene.pieces[0].points) + sum(len(p.surface.points) for p in scene.patches)
    assert n == len(points) == expected
    mesh = meshio.read(path)
    assert mesh.points.shape == (expected, 3)
    assert mesh.cells_dict["triangle"].shape == tris.shape
    assert mesh.points[:, 2].max() == pytest.approx(model_h[60.0], abs=0.01)
    assert mesh.points[:, 2].min() == pytest.approx(-model_h[40.0], abs=0.01)
    if ext == ".vtu":
        index = mesh.point_data["patch_index"]
        small = mesh.points[index == 1, 2]
        assert small.max() == pytest.approx(model_h[40.0], abs=0.01)
    assert [p.name for p in tmp_path.iterdir()] == [path.name]


def test_bad_inputs_raise_and_write_nothing(tmp_path, scene):
    with pytest.raises(InvalidInputError, match="view: 'front' is not one of iso, top, side"):
        render.RenderOptions(view="front")
    for bad in ("12", "10x10", "300x-2", "axb"):
        with pytest.raises(InvalidInputError, match="size"):
            render.parse_size(bad)
    assert render.parse_size("640x480") == (640, 480)
    with pytest.raises(InvalidInputError, match="color: 'rainbow'"):
        render.RenderOptions(colour="rainbow")
    with pytest.raises(InvalidInputError, match=r"unknown extension '\.stl'"):
        mesh_io.write_scene_mesh(tmp_path / "x.stl", scene)
    with pytest.raises(InvalidInputError, match="state 'sideways'"):
        PreviewPatch("p", (0, 0), 40.0, 0.8, "sideways")
    with pytest.raises(InvalidInputError, match="state: 'sideways'"):
        small_spec().with_state("sideways")
    with pytest.raises(InvalidInputError, match="fill"):
        build_scene(PreviewSpec((), (PreviewPatch("p", (0, 0), 40.0, 1.4),)))
    with pytest.raises(InvalidInputError, match=r"unknown extension '\.jpg'"):
        single.write_figure(tmp_path / "x.jpg", single_profile(40.0, 0.8))
    assert list(tmp_path.iterdir()) == []


def test_state_switches_and_outside_the_map_solves_directly(model_h):
    spec = small_spec(states=("up", "down", "up"))
    assert [p.state for p in spec.with_state("mixed").patches] == ["up", "down", "up"]
    assert {p.state for p in spec.with_state("down").patches} == {"down"}
    prof = single_profile(40.0, 0.3)                                # fill 0.3: outside the map
    assert prof.source == "solve"
    assert prof.keypoints.h_mm == pytest.approx(solve(Patch(40.0, 0.3)).keypoints.h_mm)
    assert single_profile(40.0, 0.8).source == "map"


class _V:
    def __init__(self, severity, patches=(), pieces=()):
        self.severity, self.patches, self.pieces = severity, patches, pieces


def test_violation_status_and_point_colours(scene):
    patch_status, piece_status = colours.status_from_violations(
        [_V("warning", ("big",)), _V("error", ("big", "small"), ("front",)),
         _V("warning", (), ("front",))])
    assert patch_status == {"big": "error", "small": "error"} and piece_status == {"front": "warning"}
    rgb = colours.point_rgb(scene, patch_status, piece_status)
    assert rgb.shape == (len(scene.merged()[0]), 3)
    n_piece = len(scene.pieces[0].points)
    assert tuple(rgb[0]) == colours.FABRIC_RGB["warning"]
    start = n_piece + len(scene.patches[0].surface.points) + len(scene.patches[1].surface.points)
    assert tuple(rgb[n_piece]) == colours.STATUS_RGB["error"]
    assert tuple(rgb[start]) == colours.STATUS_RGB["ok"]            # "down" has no violation
    assert tuple(rgb[start - 1]) == colours.FABRIC_RGB["ok"]         # the blend stays grey


def test_single_patch_figure_is_deterministic(tmp_path):
    prof = single_profile(40.0, 0.8)
    for ext in (".png", ".svg"):
        a, b = tmp_path / f"a{ext}", tmp_path / f"b{ext}"
        single.write_figure(a, prof)
        single.write_figure(b, prof, state="up")
        assert a.read_bytes() == b.read_bytes()
    svg = (tmp_path / "a.svg").read_text()
    kp = prof.keypoints
    for text in (f"h = {kp.h_mm:.2f} mm", f"r_a = {kp.r_a_mm:.2f} mm", f"z_b = {kp.z_b_mm:.2f} mm"):
        assert text in svg
    single.write_figure(tmp_path / "down.png", prof, state="down")
    assert (tmp_path / "down.png").read_bytes() != (tmp_path / "a.png").read_bytes()


def test_custom_outline_is_drawn_on_the_surface():
    prof = single_profile(40.0, 0.8)
    square = np.array([[10.0, -10.0], [10.0, 10.0], [-10.0, 10.0], [-10.0, -10.0]])  # stretched mm
    line = surfaces.boundary_line(prof, (5.0, 7.0), "up", 1.7, square, step_mm=1.0)
    assert np.array_equal(line[0], line[-1]) and len(line) == 4 * 20 + 1
    mid = line[10]                                   # (10, 0) stretched: rest radius 10 / 1.7
    rest = 10.0 / 1.7
    assert mid[0] - 5.0 == pytest.approx(np.interp(rest, prof.R_mm, prof.r_mm))
    assert mid[1] == pytest.approx(7.0)
    assert mid[2] == pytest.approx(np.interp(rest, prof.R_mm, prof.z_mm))
    circle = surfaces.boundary_line(prof, (0.0, 0.0), "down", 1.7)
    assert np.hypot(circle[:, 0], circle[:, 1]) == pytest.approx(prof.keypoints.r_a_mm)
    assert circle[:, 2] == pytest.approx(-prof.keypoints.z_a_mm)


# --- reading as 3D: framing, exaggeration, colour bar, annotations, section -----------------

def _inside(camera, size, points, usable=1.0):
    px = world_to_pixel(camera, size, points)
    w, h = size
    return bool(np.all((px[:, 0] >= 0) & (px[:, 0] <= usable * w) & (px[:, 1] >= 0)
                       & (px[:, 1] <= h)))


@pytest.mark.parametrize("view", ["iso", "top", "side"])
def test_the_camera_frames_the_patches_a_patch_or_a_piece(scene, view):
    patches = np.vstack([p.surface.points for p in scene.patches])
    big = scene.patches[0].surface.points
    default = render.render_scene(scene, render.RenderOptions(view=view, size=SIZE))[1]
    assert _inside(default, SIZE, patches, render.USABLE)
    one = render.render_scene(scene, render.RenderOptions(view=view, size=SIZE, patch="big"))[1]
    assert _inside(one, SIZE, big, render.USABLE) and not _inside(one, SIZE, patches)
    px = world_to_pixel(one, SIZE, big)
    assert np.ptp(px[:, 0]) > 0.6 * render.USABLE * SIZE[0] or np.ptp(px[:, 1]) > 0.6 * SIZE[1]
    piece = render.render_scene(scene, render.RenderOptions(view=view, size=SIZE, piece="front"))[1]
    assert _inside(piece, SIZE, scene.pieces[0].points, render.USABLE)
    assert piece.parallel_scale > default.parallel_scale > one.parallel_scale


def test_a_small_patch_on_a_large_piece_fills_the_default_frame():
    piece = PreviewPiece("panel", np.array([[0, 0], [520, 0], [520, 400], [0, 400]], float))
    scene = build_scene(PreviewSpec((piece,), (PreviewPatch("pocket", (260.0, 200.0), 90.0, 1.0),)))
    camera = render.render_scene(scene, render.RenderOptions(size=(1000, 700)))[1]
    px = world_to_pixel(camera, (1000, 700), scene.patches[0].surface.points)
    assert np.ptp(px[:, 0]) > 0.6 * render.USABLE * 1000          # was about 90 px of 1000


def test_frame_points_refuses_unknown_names(scene):
    with pytest.raises(InvalidInputError, match="no patch 'nope' in the design; it has big, small, down"):
        frame_points(scene, patch="nope")
    with pytest.raises(InvalidInputError, match="no piece 'back' in the design; it has front"):
        frame_points(scene, piece="back")
    with pytest.raises(InvalidInputError, match="not both"):
        render.RenderOptions(piece="front", patch="big")


def test_exaggeration_stretches_the_drawn_heights_only(scene):
    opts = dict(view="side", size=SIZE, patch="big", annotate=False)
    flat, cam1 = render.render_scene(scene, render.RenderOptions(**opts))
    tall, cam3 = render.render_scene(scene, render.RenderOptions(exaggerate=3.0, **opts))
    assert not np.array_equal(flat, tall)
    h = scene.patches[0].height_mm
    top1 = world_to_pixel(cam1, SIZE, [[50.0, 60.0, h]])[0, 1]
    top3 = world_to_pixel(cam3, SIZE, [[50.0, 60.0, 3 * h]])[0, 1]
    base1 = world_to_pixel(cam1, SIZE, [[50.0, 60.0, 0.0]])[0, 1]
    base3 = world_to_pixel(cam3, SIZE, [[50.0, 60.0, 0.0]])[0, 1]
    assert (base3 - top3) > 1.5 * (base1 - top1)                   # the dome drawn taller
    for bad in (0.5, 51.0, float("nan")):
        with pytest.raises(InvalidInputError, match="exaggerate"):
            render.RenderOptions(exaggerate=bad)


def test_colour_bar_spans_only_the_heights_there_are():
    h = {}
    for states in (("up", "up", "up"), ("down", "down", "down"), ("up", "up", "down")):
        sc = build_scene(small_spec(states))
        cmap, clim = colours.height_scale(sc)
        h[states[2] + states[0]] = clim
        top = max(abs(p.height_mm) for p in sc.patches)
        if states[0] == states[2]:
            assert (clim == (0.0, pytest.approx(top))) if states[0] == "up" else \
                (clim == (pytest.approx(-top), 0.0))
            assert np.allclose(cmap(0.0 if states[0] == "up" else 1.0)[:3],
                               matplotlib.colormaps[colours.HEIGHT_CMAP](0.5)[:3], atol=0.02)
        else:
            assert clim == colours.height_clim(sc)
    assert colours.height_scale(build_scene(PreviewSpec(small_spec().pieces, ()))) is None


def test_overlay_scale_bar_ids_and_note(scene):
    from stitchswitch.preview3d import overlay

    assert [overlay.nice_length_mm(v) for v in (0.7, 1.0, 3.9, 19.9, 20.0, 73.0, 480.0)] == \
        [0.5, 1.0, 2.0, 10.0, 20.0, 50.0, 200.0]
    assert overlay.height_note(1.0) == "heights to scale (x 1)"
    assert overlay.height_note(2.5) == "heights exaggerated x 2.5"
    opts = dict(view="top", size=SIZE, lighting=False, legend=False)
    plain, camera = render.render_scene(scene, render.RenderOptions(annotate=False, **opts))
    marked, _ = render.render_scene(scene, render.RenderOptions(**opts))
    diff = np.any(plain != marked, axis=2)
    w, h = SIZE
    assert diff[int(0.85 * h):, : int(0.5 * w)].any()              # the scale bar, bottom left
    assert diff[: int(0.1 * h), : int(0.6 * w)].any()              # the note, top left
    for p in scene.patches:                                         # each id just above its apex
        col, row = world_to_pixel(camera, SIZE, [[*p.surface.centre_mm, max(p.height_mm, 0)]])[0]
        col, row = int(round(col)), int(round(row))
        assert diff[max(row - 25, 0):row, col - 12:col + 12].any(), p.id
    per_px = overlay.mm_per_pixel(camera, SIZE)
    bar = np.flatnonzero(np.all(marked[int(h - 0.05 * h)] == 0, axis=1))   # the bar's row
    length = overlay.nice_length_mm(overlay.SCALE_BAR_FRACTION * w * per_px)
    assert (bar.max() - bar.min()) * per_px == pytest.approx(length, rel=0.05)


def test_section_through_a_patch_has_the_models_height(scene, model_h):
    segs, owner, rest = single.section_segments(scene, "big")
    mine = owner == 0
    assert segs[mine][:, :, 1].max() == pytest.approx(model_h[60.0], abs=0.01)
    assert segs[mine][:, :, 1].max() == pytest.approx(scene.patches[0].height_mm, abs=1e-4)  # f32
    assert (rest[mine] <= scene.patches[0].profile.boundary_radius_mm).any()
    assert (owner == -1).any() and (owner == 1).any()                # fabric and the neighbour
    down = single.section_segments(scene, "down")
    assert down[0][down[1] == 2][:, :, 1].min() == pytest.approx(-model_h[40.0], abs=0.01)
    a = single.section_bytes(scene, "big", (500, 300))
    assert a == single.section_bytes(scene, "big", (500, 300)) and a.startswith(b"\x89PNG")
    assert a != single.section_bytes(scene, "big", (500, 300), exaggerate=3.0)
    img = np.asarray(__import__("PIL.Image", fromlist=["Image"]).open(__import__("io").BytesIO(a)))
    assert img.shape[:2] == (300, 500) and len(np.unique(img.reshape(-1, img.shape[2]), axis=0)) > 20
    with pytest.raises(InvalidInputError, match="no patch 'nope'"):
        single.section_segments(scene, "nope")
