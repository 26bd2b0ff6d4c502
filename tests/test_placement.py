"""Placement: grid and polyline centres, centroids, ids, and the paper's two applications."""

import numpy as np
import pytest

from stitchswitch.errors import InvalidInputError
from stitchswitch.layout.check.constraints import check_design
from stitchswitch.layout.garment.design import Design, PatchSpec, PieceSpec
from stitchswitch.layout.garment.patterns import button_array, button_pitch_mm, pocket_patch
from stitchswitch.layout.garment.placement import (
    grid_centres,
    new_ids,
    piece_centroid,
    place_along,
    place_at,
    place_grid,
    polyline_centres,
)

from helpers import EXTERNAL

DXF = EXTERNAL / "dxf"
ETA = 1.7


def panel(w=300.0, h=200.0, name="panel") -> Design:
    return Design(1, [PieceSpec(name, "", "test", [[0, 0], [w, 0], [w, h], [0, h]])], [])


def test_grid_centres_are_centred_and_pitched():
    c = grid_centres(3, 4, 20.0, (100.0, 50.0))
    assert c.shape == (12, 2)
    np.testing.assert_allclose(c.mean(axis=0), [100.0, 50.0])
    np.testing.assert_allclose(np.diff(c[:4, 0]), 20.0)            # along a row
    np.testing.assert_allclose(c[::4, 1], [70.0, 50.0, 30.0])       # rows from the top
    c2 = grid_centres(2, 2, (10.0, 30.0), (0.0, 0.0))
    np.testing.assert_allclose(c2, [[-5, 15], [5, 15], [-5, -15], [5, -15]])


@pytest.mark.parametrize("args,message", [
    ((0, 2, 10.0, (0, 0)), "rows: 0 must be a positive integer"),
    ((2, 2.5, 10.0, (0, 0)), "cols: 2.5 must be a positive integer"),
    ((2, 2, -1.0, (0, 0)), "pitch_mm: -1.0 must be > 0"),
    ((2, 2, float("nan"), (0, 0)), "pitch_mm: nan is not a finite number"),
])
def test_grid_bad_input(args, message):
    with pytest.raises(InvalidInputError, match=message.replace(".", r"\.")):
        grid_centres(*args)


def test_polyline_centres_follow_arc_length():
    pts = [(0, 0), (30, 0), (30, 40)]                      # length 70, a corner at 30
    c = polyline_centres(pts, 20.0)
    np.testing.assert_allclose(c, [[0, 0], [20, 0], [30, 10], [30, 30]])
    exact = polyline_centres([(0, 0), (100, 0)], 25.0)     # the end point when it is on pitch
    np.testing.assert_allclose(exact[:, 0], [0, 25, 50, 75, 100])
    with pytest.raises(InvalidInputError, match="at least 2 points"):
        polyline_centres([(0, 0)], 5.0)
    with pytest.raises(InvalidInputError, match="zero length"):
        polyline_centres([(1, 1), (1, 1)], 5.0)


def test_piece_centroid():
    assert piece_centroid([[0, 0], [300, 0], [300, 200], [0, 200]]) == pytest.approx((150, 100))
    # an L made of a 20x10 and a 10x10 square: centroid ((10*5 + ... ) / area)
    ell = [[0, 0], [20, 0], [20, 10], [10, 10], [10, 20], [0, 20]]
    cx = (200 * 10 + 100 * 5) / 300
    assert piece_centroid(ell) == pytest.approx((cx, cx))


def test_ids_continue_after_the_largest_and_are_deterministic():
    d = panel()
    d = place_at(d, "panel", (50, 50), 30, 1.0)
    d = place_at(d, "panel", (100, 50), 30, 1.0, id_prefix="btn")
    d = d.with_patches([*d.patches, PatchSpec("p7", "panel", (200, 50), 30, 1.0)])
    assert new_ids(d, 2) == ["p8", "p9"] and new_ids(d, 1, "btn") == ["btn2"]
    assert new_ids(d, 1, "q") == ["q1"]
    a = place_grid(d, "panel", 2, 2, 30.0, 20, 1.0)
    b = place_grid(d, "panel", 2, 2, 30.0, 20, 1.0)
    assert a == b and [p.id for p in a.patches[-4:]] == ["p8", "p9", "p10", "p11"]


def test_place_grid_defaults_to_the_centroid_and_keeps_the_input():
    d = panel()
    out = place_grid(d, "panel", 2, 3, 25.0, 30, 0.8, conductive="ring:0", state="down")
    assert d.patches == ()                                 # not mutated
    c = np.array([p.centre_mm for p in out.patches])
    np.testing.assert_allclose(c.mean(axis=0), [150, 100])
    assert {p.conductive for p in out.patches} == {"ring:0"}
    assert {p.state for p in out.patches} == {"down"}
    along = place_along(d, "panel", [(20, 20), (280, 20)], 65.0, 30, 1.0)
    assert [p.centre_mm for p in along.patches] == [(20, 20), (85, 20), (150, 20), (215, 20),
                                                    (280, 20)]


@pytest.mark.parametrize("kwargs,message", [
    (dict(piece="sleeve"), "no piece named 'sleeve'; the pieces are panel"),
    (dict(fill=1.4), r"fill: 1.4 is outside \(0, 1\]"),
    (dict(diameter_mm=400), r"patch p1.diameter_mm: 400.0 is outside \[5, 360\] mm"),
    (dict(conductive="blob"), "patch p1.conductive: unknown selection 'blob'"),
    (dict(state="left"), "patch p1.state: 'left' is not one of"),
    (dict(id_prefix=""), "the id prefix must not be empty"),
])
def test_place_errors_name_the_new_patch(kwargs, message):
    args = dict(piece="panel", centre_mm=(50, 50), diameter_mm=30, fill=0.8)
    extra = {k: kwargs.pop(k) for k in ("conductive", "state", "id_prefix") if k in kwargs}
    args.update(kwargs)
    with pytest.raises(InvalidInputError, match=message):
        place_at(panel(), **args, **extra)


def test_button_array_pitch_leaves_the_requested_spacing():
    """The forearm interface (paper 6.2): default pitch = footprint d / eta + spacing, so the
    spacing rule measures exactly the requested bare fabric between buttons."""
    sleeve = panel(250.0, 120.0, "sleeve")
    d = button_array(sleeve, "sleeve", 2, 3, 30.0, 1.0, spacing_mm=8.0, conductive="ring:0")
    assert [p.id for p in d.patches] == [f"button{i}" for i in range(1, 7)]
    c = np.array([p.centre_mm for p in d.patches])
    pitch = button_pitch_mm(30.0, ETA, 8.0)
    np.testing.assert_allclose(np.diff(c[:3, 0]), pitch)
    assert np.hypot(*(c[1] - c[0])) - 30.0 / ETA == pytest.approx(8.0)
    assert check_design(d) == []                           # clean with the default limits
    tight = button_array(sleeve, "sleeve", 2, 3, 30.0, 1.0, spacing_mm=3.0)
    found = check_design(tight)
    assert {v.rule for v in found} == {"spacing"}
    assert all(v.value == pytest.approx(3.0) for v in found)


def test_pocket_patch_on_the_imported_tank_front():
    """The tennis pocket (paper 6.1) as one large patch on a real pattern piece."""
    from stitchswitch.layout.garment.dxf.reader import import_dxf
    from stitchswitch.layout.garment.piece_select import select_pieces

    pieces = select_pieces(import_dxf(DXF / "WM_LOOSE_SHAPE_TANK_AAMA.DXF"), "36",
                           ["RELAXED TANK FR V2"])
    d = pocket_patch(Design(1, pieces, []), "RELAXED TANK FR V2", 90.0, 1.0)
    (pocket,) = d.patches
    assert pocket.id == "pocket1" and pocket.state == "up"
    assert pocket.centre_mm == pytest.approx(piece_centroid(pieces[0].outline_mm))
    assert check_design(d) == []
