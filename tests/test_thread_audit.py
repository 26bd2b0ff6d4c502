"""The thread audit measures what it says on synthetic plans whose answers are known by hand."""
import numpy as np
import pytest

from stitchswitch.layout.embroidery import stitches as st
from stitchswitch.layout.embroidery.sewing.audit import audit

SQUARES = [np.array([[0, 0], [2, 0], [2, 2], [0, 2]], float),
           np.array([[3, 0], [5, 0], [5, 2], [3, 2]], float)]
CENTROIDS = np.array([[1.0, 1.0], [4.0, 1.0]])


def _plan(records, ties=None, conductive=False):
    xy = np.array([p for _, p in records], float)
    cmd = np.array([c for c, _ in records], np.int8)
    thread = st.CONDUCTIVE_THREAD if conductive else st.NORMAL_THREAD
    return st.StitchPlan(xy, cmd, (thread,), 860.0, None if ties is None else np.array(ties))


def test_a_stitch_over_the_gap_is_one_crossing_of_the_gap_width():
    plan = _plan([(st.JUMP, (0.5, 1)), (st.STITCH, (0.5, 1)), (st.STITCH, (1.8, 1)),
                  (st.STITCH, (3.2, 1)), (st.STITCH, (4.5, 1)), (st.TRIM, (4.5, 1)),
                  (st.END, (4.5, 1))], conductive=True)
    a = audit(plan, SQUARES, np.array([True, True]), CENTROIDS, 3.0)
    assert a.gap_crossings == 1 and a.gap_crossing_mm == pytest.approx(1.0)
    assert a.electrode_components == (1,) and a.trims == 1
    assert a.short_stitches == 1            # the zero-length first penetration, not marked tie


def test_a_trim_splits_the_electrode_and_a_float_still_crosses():
    trimmed = _plan([(st.JUMP, (0.5, 1)), (st.STITCH, (0.5, 1)), (st.STITCH, (1.5, 1)),
                     (st.TRIM, (1.5, 1)), (st.JUMP, (3.5, 1)), (st.STITCH, (3.5, 1)),
                     (st.STITCH, (4.5, 1)), (st.END, (4.5, 1))], conductive=True)
    a = audit(trimmed, SQUARES, np.array([True, True]), CENTROIDS, 3.0)
    assert a.gap_crossings == 0 and a.electrode_components == (2,)
    floated = _plan([(st.JUMP, (0.5, 1)), (st.STITCH, (0.5, 1)), (st.STITCH, (1.5, 1)),
                     (st.JUMP, (3.5, 1)), (st.STITCH, (3.5, 1)), (st.STITCH, (4.5, 1)),
                     (st.END, (4.5, 1))], conductive=True)
    b = audit(floated, SQUARES, np.array([True, True]), CENTROIDS, 3.0)
    assert b.gap_crossings == 1 and b.gap_crossing_mm == pytest.approx(1.0)
    assert b.electrode_components == (1,)


def test_ties_counted_and_excluded_from_short_stitches():
    rec = [(st.JUMP, (0.5, 1)), (st.STITCH, (0.5, 1)), (st.STITCH, (0.7, 1)),
           (st.STITCH, (0.5, 1)), (st.STITCH, (0.7, 1)), (st.STITCH, (1.9, 1)),
           (st.STITCH, (1.95, 1)), (st.END, (1.95, 1))]
    ties = [False, True, True, True, True, False, False, False]
    a = audit(_plan(rec, ties), SQUARES, np.array([False, False]), CENTROIDS, 3.0)
    assert a.ties == 1 and a.min_tie_stitches == 3
    assert a.min_tie_stitch_mm == pytest.approx(0.2)
    assert a.short_stitches == 1            # 1.9 -> 1.95 (0.1 mm after rounding)
    assert a.electrode_components == ()
