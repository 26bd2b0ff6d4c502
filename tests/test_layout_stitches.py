import math

import numpy as np
import pytest

from stitchswitch.errors import InvalidInputError
from stitchswitch.layout.embroidery.patch_geometry import ByRing, make_patch
from stitchswitch.layout.embroidery.stitches import (
    COLOR_CHANGE,
    CONDUCTIVE_THREAD,
    END,
    JUMP,
    STITCH,
    TRIM,
    StitchParams,
    fill_piece,
    plan_stitches,
)


@pytest.fixture(scope="module")
def plan():
    return plan_stitches(make_patch(40.0, 0.8, 5.0, conductive=ByRing((0, 1))))


def _moves(plan):
    d = np.linalg.norm(np.diff(plan.xy_mm, axis=0), axis=1)
    return d, plan.commands[1:], plan.commands[:-1]


def test_no_stitch_longer_than_max_and_ends(plan):
    L = plan.stitch_lengths_mm()
    assert L.max() <= 3.5 + 1e-9
    assert plan.commands[-1] == END and np.count_nonzero(plan.commands == END) == 1


def test_every_run_is_jump_tie_in_stitches_tie_off_trim(plan):
    # every jump follows a trim or colour change; after it a penetration in place, then a tie-in
    # of 4 stitches back and forth of 0.5 - 0.7 mm; before every trim a tie-off the same way
    jumps = np.flatnonzero(plan.commands == JUMP)
    for j in jumps[1:]:
        assert plan.commands[j - 1] in (TRIM, COLOR_CHANGE)
    for j in jumps:
        assert plan.commands[j + 1] == STITCH
        np.testing.assert_allclose(plan.xy_mm[j + 1], plan.xy_mm[j])
        lock = np.linalg.norm(np.diff(plan.xy_mm[j + 1:j + 6], axis=0), axis=1)
        assert plan.ties[j + 1:j + 6].all()
        assert np.all(lock >= 0.5 - 1e-9) and np.all(lock <= 0.7 + 0.15)
    for t in np.flatnonzero(plan.commands == TRIM):
        np.testing.assert_allclose(plan.xy_mm[t - 1], plan.xy_mm[t - 3])
        assert plan.ties[t - 4:t].all()


def test_no_short_stitch_outside_ties_and_on_the_file_grid(plan):
    L = np.linalg.norm(np.diff(plan.xy_mm, axis=0, prepend=plan.xy_mm[:1]), axis=1)
    fill = (plan.commands == STITCH) & ~plan.ties
    assert L[fill].min() >= 0.3 - 1e-9
    np.testing.assert_allclose(plan.xy_mm * 10, np.round(plan.xy_mm * 10), atol=1e-9)


def test_colour_change_and_threads(plan):
    assert plan.color_changes == 1
    assert plan.threads[1] is CONDUCTIVE_THREAD
    cc = int(np.flatnonzero(plan.commands == COLOR_CHANGE)[0])
    assert plan.commands[cc - 1] == TRIM
    assert any("bobbin" in n for n in plan.fabrication_notes())


def test_stitches_inside_patch(plan):
    r = np.hypot(plan.xy_mm[:, 0], plan.xy_mm[:, 1])
    # pull compensation (0.1 mm) and the 0.1 mm grid of the files
    assert r.max() <= 20.0 + 0.1 + 0.075


def test_report(plan):
    assert plan.sewing_time_min == pytest.approx(plan.stitch_count / 860.0 + plan.trim_count * 6.0 / 60
                                                 + plan.color_changes * 60.0 / 60)
    assert plan.thread_length_mm == pytest.approx(plan.stitch_lengths_mm().sum())
    # the fill covers the stitched area at the row spacing: thread >= area / spacing; satin
    # pieces (boundary slivers) lay up to twice that, row links and locks add a little
    geom = make_patch(40.0, 0.8, 5.0)
    bare = plan_stitches(geom, StitchParams(underlay=False))
    assert 1.0 < bare.thread_length_mm / (geom.stitched_area_mm2 / 0.4) < 1.6
    assert plan.thread_length_mm > bare.thread_length_mm              # the underlay


def test_deterministic(plan):
    again = plan_stitches(make_patch(40.0, 0.8, 5.0, conductive=ByRing((0, 1))))
    np.testing.assert_array_equal(again.xy_mm, plan.xy_mm)
    np.testing.assert_array_equal(again.commands, plan.commands)


def test_tatami_rows_staggered_and_spaced():
    tri = np.array([[0.0, 0.0], [10.0, 0.0], [5.0, 5 * math.sqrt(3)]])
    pts = fill_piece(tri, StitchParams(underlay=False, pull_compensation_mm=0.0))
    ys = np.unique(np.round(pts[:, 1], 9))
    assert np.diff(ys).max() == pytest.approx(5 * math.sqrt(3) / 22, rel=1e-6)   # ceil(h / 0.4) rows
    assert np.diff(ys).max() <= 0.4
    seg = np.linalg.norm(np.diff(pts, axis=0), axis=1)
    assert seg.max() <= 3.5 + 1e-9 and seg.min() >= 0.3 - 1e-9 or seg.min() > 0
    # interior penetrations of consecutive rows are offset by a third of the stitch length
    rows = [np.sort(pts[np.isclose(pts[:, 1], y), 0])[1:-1] for y in ys[:3]]
    m = [(r[0] % 3.5) for r in rows]
    assert (m[1] - m[0]) % 3.5 == pytest.approx(3.5 / 3, abs=1e-9)


def test_small_piece_is_satin():
    tri = np.array([[0.0, 0.0], [2.0, 0.0], [1.0, math.sqrt(3)]])
    pts = fill_piece(tri, StitchParams(underlay=False))
    # a zigzag from edge to edge: every stitch crosses the piece
    assert len(pts) == math.ceil(math.sqrt(3) / 0.2)
    left = pts[::2, 0] <= pts[1::2, 0].min() if len(pts) > 1 else True
    assert np.all(left)


@pytest.mark.parametrize("side, kind", [(10.0, "tatami underlay"), (5.0, "edge run"),
                                        (3.0, "centre walk")])
def test_underlay_first_and_of_the_right_kind(side, kind):
    tri = np.array([[0.0, 0.0], [side, 0.0], [side / 2, side * math.sqrt(3) / 2]])
    plain = fill_piece(tri, StitchParams(underlay=False))
    under = fill_piece(tri, StitchParams())
    assert len(under) > len(plain)
    extra = under[:len(under) - len(plain)]
    if kind == "centre walk":            # up the middle, then the zigzag reversed
        np.testing.assert_allclose(extra[:, 0], side / 2, atol=1e-9)
        np.testing.assert_array_equal(under[len(extra):], plain[::-1])
        return
    np.testing.assert_array_equal(under[len(extra):], plain)
    ys = np.unique(np.round(extra[:, 1], 6))
    if kind == "edge run":
        np.testing.assert_allclose(extra[0], extra[-1])
    else:                                # rows at right angles: vertical, 1.5 mm apart
        xs = np.unique(np.round(extra[:, 0], 6))
        assert len(xs) < len(ys) and np.diff(xs).max() <= 1.5 + 1e-9


def test_bad_params():
    with pytest.raises(InvalidInputError):
        StitchParams(row_spacing_mm=0.0)
