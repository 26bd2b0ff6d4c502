"""Hoopings and order planned together for the fewest frame conflicts: on small cases the plan
is checked against an exhaustive search over every set of candidate placements and every order
(so it reaches 0 wherever a conflict-free plan exists), the beam search on larger ones never
does worse than grouping for the fewest hoopings first, and the plan's count is what the
stitching order reports."""
import itertools

import numpy as np
import pytest

from stitchswitch.layout.embroidery.hoop_spec import Hoop
from stitchswitch.layout.fabrication.grouping import candidates, conflict_plan
from stitchswitch.layout.fabrication.grouping.footprints import Footprint, StretchedPiece
from stitchswitch.layout.fabrication.grouping.group import group
from stitchswitch.layout.fabrication.order import order_hoopings

SQ = Hoop("SQ", 140.0, 140.0, 2, margin_mm=5.0, frame_width_mm=20.0)
RE = Hoop("RE", 140.0, 200.0, 2, margin_mm=5.0, frame_width_mm=20.0)
PIECE = StretchedPiece("front", np.array([[0, 0], [520, 0], [520, 440], [0, 440]], dtype=float))


def dense_feet(n, seed, box=(150.0, 370.0, 150.0, 290.0)):
    """n discs (d 20..40 mm, 8 mm apart) packed in a small box of a large piece: frames of
    one hooping land on the others."""
    rng = np.random.default_rng(seed)
    x0, x1, y0, y1 = box
    rows = []
    while len(rows) < n:
        d = rng.uniform(20.0, 40.0)
        x, y = rng.uniform(x0, x1), rng.uniform(y0, y1)
        if all(np.hypot(x - a, y - b) >= (d + c) / 2 + 8.0 for a, b, c in rows):
            rows.append((x, y, d))
    return tuple(Footprint(f"p{i}", "front", (float(x), float(y)), float(d))
                 for i, (x, y, d) in enumerate(rows))


def brute_force(holds, touches):
    """The least (conflicts, hoopings) over every set of distinct candidates and every order,
    each patch stitched by the last hooping of the order that holds it (stitching a patch
    later never adds a conflict, so that assignment is the best for the order)."""
    m, n = holds.shape
    best = None
    for k in range(1, n + 1):
        for subset in itertools.combinations(range(m), k):
            if not holds[list(subset)].any(axis=0).all():
                continue
            for order in itertools.permutations(subset):
                owner = {}
                for step, c in enumerate(order):
                    for i in np.flatnonzero(holds[c]):
                        owner[int(i)] = step               # the last holder wins
                if len(set(owner.values())) < k:
                    continue                               # a hooping stitching nothing
                done = np.zeros(n, dtype=bool)
                conflicts = 0
                for step, c in enumerate(order):
                    conflicts += int((touches[c] & done).sum())
                    for i, s in owner.items():
                        if s == step:
                            done[i] = True
                key = (conflicts, k)
                if best is None or key < best:
                    best = key
        if best is not None and best[0] == 0:
            break                     # more hoopings cannot beat a conflict-free plan
    return best


@pytest.mark.parametrize("seed", range(8))
def test_exact_plan_matches_exhaustive_search(seed):
    feet = dense_feet(4, seed)
    cands = candidates.generate(feet, (PIECE,), (SQ,))
    want = brute_force(cands.holds, cands.touches)
    plan = conflict_plan.plan_piece(cands.holds, cands.touches, np.zeros(len(cands), int),
                                    np.arange(len(feet)))
    assert plan.exact and (plan.conflicts, len(plan.steps)) == want
    # the whole pipeline: grouping, then the stitching order, reports the same conflicts
    g = group(feet, (PIECE,), (SQ,), "garment")
    order = order_hoopings(g.hoopings, feet)
    assert (len(order.conflicts), g.count) == want
    assert g.report.conflicts == want[0] and g.report.conflicts_exact


@pytest.mark.parametrize("n, seed, hoops, want", [
    (5, 11, (SQ,), (0, 3)),          # a conflict-free plan needs one hooping more
    (6, 9, (SQ, RE), (0, 2)),        # as many hoopings, other placements
])
def test_conflict_free_plan_found_where_fewest_hoopings_has_conflicts(n, seed, hoops, want):
    """Grouping for the fewest hoopings first leaves a frame conflict in these layouts whose
    exhaustive optimum has none: the plan reaches 0."""
    feet = dense_feet(n, seed)
    before = group(feet, (PIECE,), hoops, "garment", avoid_conflicts=False)
    after = group(feet, (PIECE,), hoops, "garment")
    assert len(order_hoopings(before.hoopings, feet).conflicts) == 1 and before.count == 2
    assert (len(order_hoopings(after.hoopings, feet).conflicts), after.count) == want
    assert after.report.fewest_hoopings == 2 and after.report.fewest_hoopings_conflicts == 1
    cands = candidates.generate(feet, (PIECE,), hoops)
    assert brute_force(cands.holds, cands.touches) == want


def test_beam_never_worse_than_fewest_hoopings():
    """Beyond the exact size (forced here) the beam search, with the fewest-hoopings
    grouping's own placements planned alongside, never has more conflicts."""
    feet = dense_feet(9, 3, box=(120.0, 400.0, 120.0, 320.0))
    cands = candidates.generate(feet, (PIECE,), (SQ, RE))
    rank = np.zeros(len(cands), int)
    exact = conflict_plan.plan_piece(cands.holds, cands.touches, rank, np.arange(9))
    beam = conflict_plan.plan_piece(cands.holds, cands.touches, rank, np.arange(9),
                                    exact_max=0)
    assert exact.exact and not beam.exact
    assert exact.conflicts <= beam.conflicts
    before = group(feet, (PIECE,), (SQ, RE), "garment", avoid_conflicts=False)
    c_before = len(order_hoopings(before.hoopings, feet).conflicts)
    assert exact.conflicts <= c_before


def test_plan_cost_counts_frames_on_stitched_patches():
    touches = np.array([[False, True], [False, False]])     # candidate 0's frame on patch 1
    assert conflict_plan.plan_cost(((1, (1,)), (0, (0,))), touches) == 1
    assert conflict_plan.plan_cost(((0, (0,)), (1, (1,))), touches) == 0
