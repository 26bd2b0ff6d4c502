"""Hoop grouping: garment mode against a brute-force optimum, free mode on cases with a known
optimum, the greedy baselines and fallback, validity of every grouping, impossible cases."""
import itertools

import numpy as np
import pytest
import shapely

from stitchswitch.errors import InvalidInputError
from stitchswitch.layout.embroidery.hoop_spec import Hoop
from stitchswitch.layout.embroidery.machines import default_machine
from stitchswitch.layout.fabrication.grouping import free as hoop_free
from stitchswitch.layout.fabrication.grouping import garment as hoop_garment
from stitchswitch.layout.fabrication.grouping import greedy as hoop_greedy
from stitchswitch.layout.fabrication.grouping.footprints import Footprint, StretchedPiece
from stitchswitch.layout.fabrication.grouping.group import group
from stitchswitch.layout.fabrication.grouping.mip import CoverSolution

SQ = Hoop("SQ", 140.0, 140.0, 2, margin_mm=5.0, frame_width_mm=20.0)
RE = Hoop("RE", 140.0, 200.0, 2, margin_mm=5.0, frame_width_mm=20.0)
HOOPS = default_machine().hoops


def rect_piece(w, h, name="front"):
    return StretchedPiece(name, np.array([[0, 0], [w, 0], [w, h], [0, h]], dtype=float))


def feet_of(rows, piece="front"):
    return tuple(Footprint(f"p{i}", piece, (float(x), float(y)), float(d))
                 for i, (x, y, d) in enumerate(rows))


def random_feet(n, seed, w=900.0, h=900.0, dmin=15.0, dmax=50.0, gap=8.0, edge=45.0):
    rng = np.random.default_rng(seed)
    rows = []
    while len(rows) < n:
        d = rng.uniform(dmin, dmax)
        x = rng.uniform(edge + d / 2, w - edge - d / 2)
        y = rng.uniform(edge + d / 2, h - edge - d / 2)
        if all(np.hypot(x - a, y - b) >= (d + c) / 2 + gap for a, b, c in rows):
            rows.append((x, y, d))
    return feet_of(rows)


def check_valid(grouping, feet, pieces, hoops, spacing_mm=10.0):
    """Every patch in exactly one hooping, inside its usable area; frames on the fabric."""
    by_id = {f.id: f for f in feet}
    seen = [pid for h in grouping.hoopings for pid in h.patch_ids]
    assert sorted(seen) == sorted(by_id)
    for h in grouping.hoopings:
        assert h.hoop in hoops
        w, hh = h.hoop.usable_mm()
        for pid, (x, y) in zip(h.patch_ids, h.positions_mm):
            r = by_id[pid].radius_mm
            assert abs(x) <= w / 2 - r + 1e-6 and abs(y) <= hh / 2 - r + 1e-6
        if grouping.mode == "garment":
            got = h.to_hoop(np.array([by_id[p].centre_mm for p in h.patch_ids]))
            assert np.allclose(got, h.positions_mm)
            ow, oh = h.hoop.outer_mm(h.orientation_deg)
            piece = next(p for p in pieces if p.name == h.piece)
            box = shapely.box(h.centre_mm[0] - ow / 2, h.centre_mm[1] - oh / 2,
                              h.centre_mm[0] + ow / 2, h.centre_mm[1] + oh / 2)
            assert shapely.Polygon(piece.outline_mm).contains(box)
        else:
            discs = [(np.array(p), by_id[i].radius_mm) for i, p in zip(h.patch_ids, h.positions_mm)]
            for (a, ra), (b, rb) in itertools.combinations(discs, 2):
                assert np.linalg.norm(a - b) >= ra + rb + spacing_mm - 1e-6


def brute_force_garment(feet, hoops):
    """Fewest hoopings by enumerating set partitions (large piece: only the hoop sizes matter)."""
    c = np.array([f.centre_mm for f in feet])
    r = np.array([f.radius_mm for f in feet])
    sizes = [h.usable_mm(o) for h in hoops for o in h.orientations]

    def ok(block):
        b = list(block)
        sx = (c[b, 0] + r[b]).max() - (c[b, 0] - r[b]).min()
        sy = (c[b, 1] + r[b]).max() - (c[b, 1] - r[b]).min()
        return any(sx <= w + 1e-9 and sy <= h + 1e-9 for w, h in sizes)

    best = [len(feet)]

    def rec(i, blocks):
        if len(blocks) >= best[0]:
            return
        if i == len(feet):
            best[0] = len(blocks)
            return
        for blk in blocks:
            blk.append(i)
            if ok(blk):
                rec(i + 1, blocks)
            blk.pop()
        blocks.append([i])
        rec(i + 1, blocks)
        blocks.pop()

    rec(0, [])
    return best[0]


@pytest.mark.parametrize("seed", range(6))
def test_garment_matches_brute_force(seed):
    rng = np.random.default_rng(100 + seed)
    rows = [(rng.uniform(120, 480), rng.uniform(120, 480), rng.uniform(15, 45)) for _ in range(8)]
    feet = feet_of(rows)
    pieces = (rect_piece(600, 600),)
    g = group(feet, pieces, (SQ, RE), "garment")
    assert g.report.method == "mip" and g.report.optimal and g.report.mip_gap == pytest.approx(0)
    assert g.count == brute_force_garment(feet, (SQ, RE))
    assert g.count <= g.report.greedy_hoopings
    assert g.report.hoopings_lower_bound == g.count
    check_valid(g, feet, pieces, (SQ, RE))


def test_garment_row_known_optimum_turn_and_smaller_hoop():
    # 7 patches of 20 mm, 50 mm apart along x: at most 3 fit the 130 mm usable width of SQ
    feet = feet_of([(100 + 50 * i, 300, 20) for i in range(7)])
    pieces = (rect_piece(700, 600),)
    g = group(feet, pieces, (SQ,), "garment")
    assert g.count == 3
    check_valid(g, feet, pieces, (SQ,))
    # RE turned 90 degrees has 190 mm along x: 4 per hooping -> 2, both turned
    g2 = group(feet, pieces, (SQ, RE), "garment")
    assert g2.count == 2 and g2.hoop_types == 1
    assert all(h.hoop.name == "RE" and h.orientation_deg == 90 for h in g2.hoopings)
    check_valid(g2, feet, pieces, (SQ, RE))
    # 3 of them fit either hoop: the smaller one is taken
    g3 = group(feet[:3], pieces, (RE, SQ), "garment")
    assert g3.count == 1 and g3.hoopings[0].hoop.name == "SQ"


def test_garment_finds_a_narrow_strip_of_allowed_positions():
    """Two 40 mm discs 170 mm apart on a 510 x 425 mm piece fit one RE36b (outer 250 x 410 mm)
    only with the field centre in a 15 mm strip (y 205..220), between the points of the 5 x 5
    grid over the set's feasible box (y 117..257): the 17 x 17 grid finds it."""
    feet = feet_of([(170, 102, 40), (170, 272, 40)])
    g = group(feet, (rect_piece(510, 425),), (default_machine().hoop("RE36b"),), "garment")
    assert g.count == 1 and 205 <= g.hoopings[0].centre_mm[1] <= 220


def test_garment_several_pieces_never_share_a_hooping():
    a = feet_of([(150, 150, 20)], "front")
    b = tuple(Footprint("q0", "back", (160.0, 150.0), 20.0) for _ in range(1))
    pieces = (rect_piece(300, 300, "front"), rect_piece(300, 300, "back"))
    g = group(a + b, pieces, (SQ,), "garment")
    assert g.count == 2 and {h.piece for h in g.hoopings} == {"front", "back"}


@pytest.mark.parametrize("seed", [1, 2])
def test_garment_mip_never_worse_than_greedy(seed):
    feet = random_feet(20, seed)
    pieces = (rect_piece(900, 900),)
    g = group(feet, pieces, HOOPS, "garment", time_limit_s=10)
    assert g.report.method == "mip"
    assert g.count <= g.report.greedy_hoopings
    check_valid(g, feet, pieces, HOOPS)


def test_greedy_baselines_are_covers():
    from stitchswitch.layout.fabrication.grouping import candidates as hoop_candidates
    feet = random_feet(15, 3)
    cands = hoop_candidates.generate(feet, (rect_piece(900, 900),), HOOPS)
    for chosen in (hoop_greedy.greedy_cover(cands),
                   hoop_greedy.first_fit_decreasing_garment(cands, [f.diameter_mm for f in feet])):
        assert cands.holds[chosen].any(axis=0).all()


def test_garment_fallback_when_highs_has_no_solution(monkeypatch):
    feet = random_feet(15, 4)
    pieces = (rect_piece(900, 900),)
    stopped = CoverSolution(None, "user_limit", False, None, None, None, 0.01)
    monkeypatch.setattr(hoop_garment, "solve_cover", lambda *a, **k: stopped)
    g = group(feet, pieces, HOOPS, "garment", time_limit_s=0.5)
    assert g.report.method == "greedy-fallback" and not g.report.optimal
    assert g.report.mip_gap is None and "greedy" in g.report.note
    assert g.count <= g.report.greedy_hoopings
    check_valid(g, feet, pieces, HOOPS)


def test_real_time_limit_keeps_the_guarantees():
    feet = random_feet(40, 5)
    pieces = (rect_piece(900, 900),)
    g = group(feet, pieces, HOOPS, "garment", time_limit_s=0.05)
    assert g.report.time_limit_s == 0.05
    assert g.count <= g.report.greedy_hoopings
    check_valid(g, feet, pieces, HOOPS)


def test_free_known_optima():
    # discs of 60 mm, 10 mm apart, in a 130 mm usable square: 4 fit (2 x 2), 5 do not
    feet4 = feet_of([(0, 0, 60)] * 4)
    g = group(feet4, (), (SQ,), "free", spacing_mm=10.0)
    assert g.count == 1 and g.report.optimal
    check_valid(g, feet4, (), (SQ,))
    feet5 = feet_of([(0, 0, 60)] * 5)
    g = group(feet5, (), (SQ,), "free", spacing_mm=10.0)
    assert g.count == 2
    check_valid(g, feet5, (), (SQ,))
    # two 100 mm discs never share a 130 mm square: the clique bound proves 3 for 3 of them
    feet3 = feet_of([(0, 0, 100)] * 3)
    g = group(feet3, (), (SQ,), "free", spacing_mm=10.0)
    assert g.count == 3 and g.report.hoopings_lower_bound == 3


def test_free_prefers_fewer_types_then_smaller_hoops():
    feet = feet_of([(0, 0, 40)] * 3)
    g = group(feet, (), HOOPS, "free", spacing_mm=10.0)
    assert g.count == 1 and g.hoopings[0].hoop.name == "SQ14b"


@pytest.mark.parametrize("seed", [1, 2])
def test_free_never_worse_than_first_fit(seed):
    feet = random_feet(20, seed, dmin=30, dmax=80)
    g = group(feet, (), HOOPS, "free", time_limit_s=10)
    assert g.count <= g.report.greedy_hoopings
    assert g.count >= g.report.hoopings_lower_bound
    check_valid(g, feet, (), HOOPS)


def test_free_fallback(monkeypatch):
    feet = random_feet(12, 6, dmin=30, dmax=80)
    stopped = CoverSolution(None, "user_limit", False, None, None, None, 0.01)
    monkeypatch.setattr(hoop_free, "solve_cover", lambda *a, **k: stopped)
    g = group(feet, (), HOOPS, "free", time_limit_s=1.0)
    assert g.report.method == "greedy-fallback" and g.count <= g.report.greedy_hoopings
    check_valid(g, feet, (), HOOPS)


def test_lower_bound_pairs():
    assert hoop_free.pair_fits(30, 30, 140, 140)           # opposite corners: 113 >= 60
    assert not hoop_free.pair_fits(45, 45, 140, 140)        # 70 < 90
    assert not hoop_free.pair_fits(80, 10, 140, 140)        # too big alone


@pytest.mark.parametrize("mode", ["garment", "free"])
def test_patch_larger_than_every_hoop(mode):
    feet = feet_of([(300, 300, 40), (500, 300, 195)])
    with pytest.raises(InvalidInputError, match="patch 'p1': its 195 mm footprint on the stretched "
                                                "fabric fits no hoop; the roomiest is RE36b"):
        group(feet, (rect_piece(900, 900),), HOOPS, mode)


def test_patch_too_close_to_the_edge():
    feet = feet_of([(300, 300, 40), (40, 300, 30)])
    with pytest.raises(InvalidInputError, match="patch 'p1' cannot be hooped: it is too close to "
                                                "the edge of piece 'front'"):
        group(feet, (rect_piece(900, 900),), HOOPS, "garment")
    # just far enough: radius + margin + frame = 15 + 5 + 25 = 45 mm from the edge
    ok = feet_of([(300, 300, 40), (45.01, 300, 30)])
    g = group(ok, (rect_piece(900, 900),), HOOPS, "garment")
    check_valid(g, ok, (rect_piece(900, 900),), HOOPS)


def test_bad_arguments():
    feet = feet_of([(300, 300, 40)])
    with pytest.raises(InvalidInputError, match="unknown mode 'x'"):
        group(feet, (), (SQ,), "x")
    with pytest.raises(InvalidInputError, match="time limit 0 s must be positive"):
        group(feet, (), (SQ,), "free", time_limit_s=0)
    with pytest.raises(InvalidInputError, match="spacing -1 mm"):
        group(feet, (), (SQ,), "free", spacing_mm=-1)
