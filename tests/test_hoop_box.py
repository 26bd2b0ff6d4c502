"""The feasible box of a set of patches for a hoop's field centre is one helper
(``check.rules.hoopable.feasible_box`` and its grid ``box_grid``), used by the grouping's
candidate placements and by the workshop sheet's hoop reason. Proven unchanged: the candidate
placements, ``_placeable`` and the hoop reasons equal those recorded from the code before the
helper (tests/data/hoop_box/golden.json, its provenance in make_golden.py) on the two demo
designs and random layouts, and a property test compares the helper with the per-set formula
(the box as ``hoop_reason`` wrote it) and a brute-force test of which centres hold the set."""
import json
import pathlib

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from hoop_box_cases import cases
from stitchswitch.layout.check.rules import hoopable
from stitchswitch.layout.fabrication.grouping import candidates
from stitchswitch.layout.fabrication.grouping.group import group
from stitchswitch.layout.fabrication.hoop_reason import _placeable, hoop_reason

from fuzzing import FUZZ

DATA = pathlib.Path(__file__).parent / "data" / "hoop_box"
GOLDEN = json.loads((DATA / "golden.json").read_text())
CASES = cases(DATA)


def test_the_golden_file_covers_every_case_and_both_reasons_of_a_smaller_hoop():
    assert set(GOLDEN) == set(CASES)
    placeable = [p for g in GOLDEN.values() for p in g["placeable"]]
    assert any(a and not b for p in placeable for a, b in zip(*p))   # held, frame off the fabric
    reasons = [t for g in GOLDEN.values() for t in g["reasons"]]
    assert any(t.startswith("a smaller hoop") for t in reasons)
    assert any(" is the smallest hoop " in t for t in reasons)


@pytest.mark.parametrize("name", sorted(CASES))
def test_candidates_placeable_and_reasons_unchanged(name):
    feet, pieces, hoops = CASES[name]
    want = GOLDEN[name]
    c = candidates.generate(feet, pieces, hoops)
    assert c.hoop_index.tolist() == want["hoop_index"]
    assert c.orientation_deg.tolist() == want["orientation_deg"]
    assert c.piece_index.tolist() == want["piece_index"]
    assert [[float(v) for v in row] for row in c.centre_mm] == want["centre_mm"]   # bit for bit
    assert [np.flatnonzero(row).tolist() for row in c.holds] == want["holds"]
    x = np.array([f.centre_mm for f in feet], dtype=float)
    r = np.array([f.radius_mm for f in feet], dtype=float)
    for j, got in enumerate(want["placeable"]):
        held = np.flatnonzero(c.holds[j])
        piece = pieces[c.piece_index[j]]
        region = hoopable.hoop_region(piece.outline_mm, piece.blank_mm)
        assert [[bool(_placeable(h, o, x[held], r[held], reg)) for h in hoops
                 for o in h.orientations] for reg in (None, region)] == got
    g = group(feet, pieces, hoops, "garment", None)
    assert [hoop_reason(h, hoops, feet, pieces) for h in g.hoopings] == want["reasons"]


discs = st.lists(st.tuples(st.floats(-200, 200), st.floats(-200, 200), st.floats(1, 60)),
                 min_size=1, max_size=8)


@FUZZ
@given(discs=discs, w=st.floats(20, 400), h=st.floats(20, 400),
       pick=st.lists(st.lists(st.booleans(), min_size=8, max_size=8), min_size=1, max_size=4))
def test_feasible_box_is_the_per_set_box_and_holds_exactly_its_set(discs, w, h, pick):
    x, y, r = (np.array(v, dtype=float) for v in zip(*discs))
    members = np.array([row[:len(x)] for row in pick], dtype=bool)
    members[:, 0] |= ~members.any(axis=1)                 # a set has a member
    lo_x, hi_x, lo_y, hi_y = hoopable.feasible_box(members, x, y, r, w, h)
    for k, m in enumerate(members):
        # the formula as hoop_reason computed it for one set, bit for bit
        assert lo_x[k] == np.max(x[m] + r[m]) - w / 2 and hi_x[k] == np.min(x[m] - r[m]) + w / 2
        assert lo_y[k] == np.max(y[m] + r[m]) - h / 2 and hi_y[k] == np.min(y[m] - r[m]) + h / 2
        if lo_x[k] > hi_x[k] or lo_y[k] > hi_y[k]:
            continue
        cx, cy, a, b = hoopable.box_grid(lo_x[k:k + 1], hi_x[k:k + 1], lo_y[k:k + 1],
                                         hi_y[k:k + 1], 5)
        assert cx.shape == (1, 25) and a[0] == 0 and b[-1] == 1 and a[1] > a[0] and b[5] > b[0]
        held = hoopable.held(cx[0], cy[0], x, y, r, w, h)
        assert held[:, m].all()                           # every grid centre holds the set
        # just outside the box some member falls out of the field
        out = hoopable.held(np.array([lo_x[k] - 1e-3, hi_x[k] + 1e-3]),
                            np.array([cy[0, 12]] * 2), x, y, r, w, h)
        assert not out[:, m].all(axis=1).any()
