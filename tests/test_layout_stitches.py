import math

import numpy as np
import pytest

from stitchswitch.errors import InvalidInputError
from stitchswitch.layout.embroidery.ordering import nearest_neighbour, path_length, visiting_order
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


def test_travel_rule_runs_short_and_trims_long(plan):
    d, cmd, prev = _moves(plan)
    # every stitch longer than the fill's max would be a travel: none exist
    # every jump is preceded (possibly after the jump start) by a trim of the thread
    jumps = np.flatnonzero(plan.commands == JUMP)
    for j in jumps[1:]:
        assert plan.commands[j - 1] in (TRIM, COLOR_CHANGE)
    # every jump longer than the travel threshold; after it a penetration in place, then a tie-in
    for j in jumps[1:]:
        assert np.linalg.norm(plan.xy_mm[j] - plan.xy_mm[j - 1]) > 2.0
        assert plan.commands[j + 1] == STITCH
        np.testing.assert_allclose(plan.xy_mm[j + 1], plan.xy_mm[j])
        first = np.linalg.norm(plan.xy_mm[j + 4] - plan.xy_mm[j + 1])
        lock = np.linalg.norm(plan.xy_mm[j + 2] - plan.xy_mm[j + 1])
        assert lock == pytest.approx(min(0.7, first))
        np.testing.assert_allclose(plan.xy_mm[j + 3], plan.xy_mm[j + 1])
    # before every trim a tie-off: back and forth on the last stitch
    for t in np.flatnonzero(plan.commands == TRIM):
        np.testing.assert_allclose(plan.xy_mm[t - 1], plan.xy_mm[t - 3])


def test_colour_change_and_threads(plan):
    assert plan.color_changes == 1
    assert plan.threads[1] is CONDUCTIVE_THREAD
    cc = int(np.flatnonzero(plan.commands == COLOR_CHANGE)[0])
    assert plan.commands[cc - 1] == TRIM
    assert any("bobbin" in n for n in plan.fabrication_notes())


def test_stitches_inside_patch(plan):
    r = np.hypot(plan.xy_mm[:, 0], plan.xy_mm[:, 1])
    assert r.max() <= 20.0 + 1e-9


def test_report(plan):
    assert plan.sewing_time_min == pytest.approx(plan.stitch_count / 860.0)
    assert plan.thread_length_mm == pytest.approx(plan.stitch_lengths_mm().sum())
    # the fill covers the stitched area at the row spacing: thread >= area / spacing; satin
    # pieces (boundary slivers) lay up to twice that, row links and locks add a little
    geom = make_patch(40.0, 0.8, 5.0)
    assert 1.0 < plan.thread_length_mm / (geom.stitched_area_mm2 / 0.4) < 1.6


def test_deterministic(plan):
    again = plan_stitches(make_patch(40.0, 0.8, 5.0, conductive=ByRing((0, 1))))
    np.testing.assert_array_equal(again.xy_mm, plan.xy_mm)
    np.testing.assert_array_equal(again.commands, plan.commands)


def test_tatami_rows_staggered_and_spaced():
    tri = np.array([[0.0, 0.0], [10.0, 0.0], [5.0, 5 * math.sqrt(3)]])
    pts = fill_piece(tri, StitchParams())
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
    pts = fill_piece(tri, StitchParams())
    # a zigzag from edge to edge: every stitch crosses the piece
    assert len(pts) == math.ceil(math.sqrt(3) / 0.2)
    left = pts[::2, 0] <= pts[1::2, 0].min() if len(pts) > 1 else True
    assert np.all(left)


def test_underlay_runs_round_the_piece_first():
    tri = np.array([[0.0, 0.0], [10.0, 0.0], [5.0, 5 * math.sqrt(3)]])
    plain = fill_piece(tri, StitchParams())
    under = fill_piece(tri, StitchParams(underlay=True))
    assert len(under) > len(plain)
    np.testing.assert_array_equal(under[-len(plain):], plain)


def test_two_opt_never_longer_and_deterministic():
    pts = np.random.default_rng(1).random((150, 2)) * 50
    o = visiting_order(pts)
    assert sorted(o.tolist()) == list(range(150))
    nn = nearest_neighbour(pts, int(np.lexsort((pts[:, 0], pts[:, 1]))[0]))
    assert path_length(pts, o) < 0.95 * path_length(pts, nn)
    np.testing.assert_array_equal(o, visiting_order(pts))


def test_bad_params():
    with pytest.raises(InvalidInputError):
        StitchParams(row_spacing_mm=0.0)
