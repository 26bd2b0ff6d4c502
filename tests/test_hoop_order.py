"""Stitching order: frames kept off stitched patches where possible, unavoidable conflicts
reported, the exact search against brute force, and short travel inside a hooping."""
import itertools

import numpy as np
import pytest

from stitchswitch.layout.embroidery.hoop_spec import Hoop
from stitchswitch.layout.embroidery.ordering import path_length
from stitchswitch.layout.fabrication import order as hoop_order
from stitchswitch.layout.fabrication.grouping.footprints import Footprint
from stitchswitch.layout.fabrication.grouping.result import Hooping
from stitchswitch.layout.fabrication.order import order_hoopings

SQ = Hoop("SQ", 140.0, 140.0, 2, margin_mm=5.0, frame_width_mm=20.0)


def hooping(centre, feet):
    base = Hooping(SQ, 0, (), (), "front", centre)
    return base.with_patches([f.id for f in feet], base.to_hoop([f.centre_mm for f in feet]))


def foot(pid, x, y, d=20.0):
    return Footprint(pid, "front", (float(x), float(y)), d)


def test_frame_contact_forces_the_order():
    # A's field is centred at x = 100 (field 30..170, frame to 190); B's patch at x = 180 lies
    # under A's frame; B's frame (field 165..305, from 145) does not reach A's patch at x = 100
    a, b = foot("a", 100, 100), foot("b", 180, 100)
    ha, hb = hooping((100.0, 100.0), [a]), hooping((235.0, 100.0), [b])
    assert hoop_order.frame_contacts((ha, hb), (a, b)) == [[[], ["b"]], [[], []]]
    for given in ((ha, hb), (hb, ha)):
        o = order_hoopings(given, (a, b))
        assert [h.patch_ids for h in o.hoopings] == [("a",), ("b",)]   # A first: its frame is off b
        assert o.conflicts == () and o.exact


def test_unavoidable_conflict_is_reported():
    # each frame lands on the other hooping's patch (a 2-cycle): one conflict whatever the order
    a, a2, b = foot("a", 100, 100), foot("a2", 150, 60), foot("b", 180, 100)
    ha, hb = hooping((100.0, 100.0), [a, a2]), hooping((235.0, 100.0), [b])
    for h in (ha, hb):                                   # the hoopings are valid
        assert np.all(np.abs(h.positions_mm) <= 65 - 10 + 1e-9)
    contacts = hoop_order.frame_contacts((ha, hb), (a, a2, b))
    assert contacts == [[[], ["b"]], [["a2"], []]]
    o = order_hoopings((ha, hb), (a, a2, b))
    assert len(o.conflicts) == 1 and o.exact
    c = o.conflicts[0]
    assert (c.hooping, c.stitched_in) == (1, 0)
    assert set(o.hoopings[0].patch_ids) == {"a", "a2"}
    assert c.patch == "a2"                               # lexicographically first: A, then B


def brute(w):
    k = len(w)
    cost = lambda o: sum(w[a, b] for p, a in enumerate(o) for b in o[:p])  # noqa: E731
    best = min(cost(o) for o in itertools.permutations(range(k)))
    first = next(o for o in itertools.permutations(range(k)) if cost(o) == best)
    return best, list(first), cost


@pytest.mark.parametrize("seed", range(8))
def test_exact_order_is_the_lexicographically_first_minimum(seed):
    rng = np.random.default_rng(seed)
    k = int(rng.integers(3, 7))
    w = rng.integers(0, 3, (k, k)) * (rng.random((k, k)) < 0.4)
    np.fill_diagonal(w, 0)
    best, first, cost = brute(w)
    got = hoop_order._exact(w)
    assert cost(got) == best and got == first
    assert cost(hoop_order._greedy(w)) >= best


def test_greedy_beyond_the_exact_limit(monkeypatch):
    a, b = foot("a", 100, 100), foot("b", 180, 100)
    ha, hb = hooping((100.0, 100.0), [a]), hooping((235.0, 100.0), [b])
    monkeypatch.setattr(hoop_order, "EXACT_MAX", 1)
    o = order_hoopings((hb, ha), (a, b))
    assert not o.exact and [h.patch_ids for h in o.hoopings] == [("a",), ("b",)]


def test_patches_sewn_in_a_short_order():
    rng = np.random.default_rng(3)
    pts = rng.uniform(-55, 55, (9, 2))
    feet = [foot(f"p{i}", 300 + x, 300 + y, 8.0) for i, (x, y) in enumerate(pts)]
    h = hooping((300.0, 300.0), feet)
    o = order_hoopings((h,), feet)
    got = o.hoopings[0]
    assert sorted(got.patch_ids) == sorted(h.patch_ids)
    pos = dict(zip(got.patch_ids, got.positions_mm))
    assert all(np.allclose(pos[i], p) for i, p in zip(h.patch_ids, h.positions_mm))
    given = path_length(np.asarray(h.positions_mm), np.arange(9))
    ordered = path_length(np.asarray(got.positions_mm), np.arange(9))
    assert ordered < given


def test_free_mode_has_no_conflicts():
    feet = [Footprint(f"p{i}", "front", (0.0, 0.0), 30.0) for i in range(3)]
    h1 = Hooping(SQ, 0, ("p0", "p1"), ((-30.0, 0.0), (30.0, 0.0)))
    h2 = Hooping(SQ, 0, ("p2",), ((0.0, 0.0),))
    o = order_hoopings((h1, h2), feet)
    assert o.conflicts == () and [h.patch_ids for h in o.hoopings] == [("p0", "p1"), ("p2",)]
