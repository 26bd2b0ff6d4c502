"""Garment mode: patches stay where they are on the garment; choose hoop placements.

Every patch must lie, with its whole stretched footprint, inside the field-minus-margin of one
hooping, and every hoop's frame must clamp fabric all round (``candidates``). Over the
candidate placements this is a set cover (``mip``) with the lexicographic objective

    1. fewest hoopings,  2. fewest hoop types,  3. least frame overlap,

where the overlap of a placement is the number of other patches of the piece that its frame
ring touches (each one is a place where the frame may press a stitched patch, depending on the
order: ``layout.fabrication.order``); last come smaller hoops. A placement costs w1 + T * overlap + rank, with
T hoop types and rank the hoop's rank by field area (0 = smallest); w2 = n^2 T + 1 per hoop type
and w1 = T w2 + n^2 T + 1 (n patches): the lower terms of at most n hoopings stay below one unit
of the term above, so one hooping more always costs more than anything the lower objectives
can save, and so on down.

With a time limit, candidate generation and the greedy methods run first and HiGHS gets the
rest. If HiGHS stops without a solution at least as good as the best greedy one (greedy set
cover or first-fit decreasing, ``greedy``), that greedy solution is returned and the
report says "greedy-fallback". The number of hoopings is then never above the greedy one's.
"""
from __future__ import annotations

import math
import time

import numpy as np

from stitchswitch.layout.fabrication.grouping import candidates, conflict_plan, greedy
from stitchswitch.layout.fabrication.grouping.footprints import arrays
from stitchswitch.layout.fabrication.grouping.mip import solve_cover
from stitchswitch.layout.fabrication.grouping.result import Grouping, Hooping, SolveReport


def weights(n: int, n_types: int) -> tuple[int, int]:
    """(cost per hooping, cost per hoop type) of the objective above."""
    w2 = n * n * n_types + 1
    return n_types * w2 + n * n * n_types + 1, w2


def _rank(cands) -> np.ndarray:
    """Each candidate's hoop rank by field area (0 = smallest)."""
    area = np.array([h.area_mm2 for h in cands.hoops])
    rank = np.argsort(np.argsort(area, kind="stable"), kind="stable")
    return rank[cands.hoop_index]


def _key(cands, chosen) -> tuple[int, int, int, int]:
    chosen = list(chosen)
    return (len(chosen), len({int(cands.hoop_index[c]) for c in chosen}),
            int(sum(int(cands.overlap[c]) for c in chosen)),
            int(sum(int(_rank(cands)[c]) for c in chosen)))


def _hoopings(cands, chosen, feet) -> tuple[Hooping, ...]:
    """One hooping per chosen candidate; a patch held by several goes to the one where it has
    the most clearance to the margin (then the lower candidate index)."""
    chosen = sorted(int(c) for c in chosen)
    c_xy, r = arrays(feet)
    clear = np.full((len(chosen), len(feet)), -np.inf)
    for j, c in enumerate(chosen):
        hoop, o = cands.hoops[cands.hoop_index[c]], int(cands.orientation_deg[c])
        w, h = hoop.usable_mm(o)
        d = np.abs(c_xy - cands.centre_mm[c])
        room = np.minimum(w / 2 - r - d[:, 0], h / 2 - r - d[:, 1])
        clear[j] = np.where(cands.holds[c], room, -np.inf)
    owner = np.argmax(clear, axis=0)
    out = []
    for j, c in enumerate(chosen):
        members = np.flatnonzero((owner == j) & np.isfinite(clear[j]))
        if not len(members):
            continue
        hoop, o = cands.hoops[cands.hoop_index[c]], int(cands.orientation_deg[c])
        base = Hooping(hoop, o, (), (), feet[members[0]].piece,
                       (float(cands.centre_mm[c, 0]), float(cands.centre_mm[c, 1])))
        pos = base.to_hoop(c_xy[members])
        out.append(base.with_patches([feet[i].id for i in members], pos))
    return tuple(sorted(out, key=lambda hp: (hp.piece, round(hp.centre_mm[1], 6),
                                             round(hp.centre_mm[0], 6), hp.hoop.name)))


def _planned(cands, plan_steps, feet) -> tuple[Hooping, ...]:
    """Hoopings in stitching order from ``(candidate, patch indices)`` steps."""
    c_xy, _ = arrays(feet)
    out = []
    for c, members in plan_steps:
        hoop, o = cands.hoops[cands.hoop_index[c]], int(cands.orientation_deg[c])
        base = Hooping(hoop, o, (), (), feet[members[0]].piece,
                       (float(cands.centre_mm[c, 0]), float(cands.centre_mm[c, 1])))
        out.append(base.with_patches([feet[i].id for i in members],
                                     base.to_hoop(c_xy[list(members)])))
    return tuple(out)


def _plan_key(cands, steps, conflicts) -> tuple:
    chosen = [c for c, _ in steps]
    return (conflicts, *_key(cands, chosen))


def _conflict_plan(cands, feet, chosen):
    """The plan with the fewest frame conflicts, then hoopings (``conflict_plan``), per piece;
    the fewest-hoopings grouping ``chosen``, ordered the same way, competes (a beam search may
    miss it). Returns (steps, conflicts, exact, conflicts of the fewest-hoopings plan)."""
    rank = _rank(cands)
    piece_of = np.array([cands.piece_index[np.flatnonzero(cands.holds[:, i])[0]]
                         for i in range(len(feet))])
    steps, total, exact, base_total = [], 0, True, 0
    mine = np.zeros(len(cands), dtype=bool)
    mine[list(chosen)] = True
    for pi in np.unique(piece_of):
        idx = np.flatnonzero(piece_of == pi)
        rows = cands.piece_index == pi
        full = conflict_plan.plan_piece(cands.holds & rows[:, None], cands.touches, rank, idx)
        # the fewest-hoopings grouping: at most 2^k states for its k placements
        k = int((rows & mine).sum())
        base = conflict_plan.plan_piece(cands.holds & (rows & mine)[:, None], cands.touches,
                                        rank, idx, exact_max=64 if k <= 14 else 0)
        base_total += base.conflicts
        best = full
        if _plan_key(cands, base.steps, base.conflicts) < _plan_key(cands, full.steps,
                                                                     full.conflicts):
            best = base
        steps += list(best.steps)
        total += best.conflicts
        exact &= full.exact
    return tuple(steps), total, exact, base_total


def group_garment(feet, pieces, hoops, time_limit_s: float | None = None,
                  avoid_conflicts: bool = True) -> Grouping:
    """Hoopings for footprints on stretched ``pieces`` (see the module docstring); with
    ``avoid_conflicts`` (the default) the hoopings and their order are chosen for the fewest
    frame conflicts first (``conflict_plan``), else for the fewest hoopings alone."""
    t0 = time.perf_counter()
    cands = candidates.generate(tuple(feet), tuple(pieces), tuple(hoops))
    n = len(feet)
    w1, w2 = weights(n, len(hoops))
    diam = [f.diameter_mm for f in feet]
    baselines = {"greedy set cover": greedy.greedy_cover(cands),
                 "first-fit decreasing": greedy.first_fit_decreasing_garment(cands, diam)}
    ffd_count = len(baselines["first-fit decreasing"])
    best_name = min(baselines, key=lambda k: (_key(cands, baselines[k]), k))
    left = None if time_limit_s is None else max(0.05, time_limit_s - (time.perf_counter() - t0))
    cost = w1 + len(hoops) * cands.overlap + _rank(cands)
    sol = solve_cover(cands.holds, cost, cands.hoop_index, w2, left)
    use_mip = sol.chosen is not None and _key(cands, sol.chosen) <= _key(cands, baselines[best_name])
    chosen = sol.chosen if use_mip else baselines[best_name]
    bound = 1
    if sol.optimal:
        bound = len(chosen)
    elif sol.dual_bound is not None and math.isfinite(sol.dual_bound):
        bound = max(1, int(math.floor(sol.dual_bound / w1 + 1e-9)))
    if use_mip:
        note = ("optimal over the candidate placements" if sol.optimal else
                f"HiGHS stopped ({sol.status}) with a solution at least as good as the greedy "
                "methods'")
    else:
        note = (f"HiGHS stopped ({sol.status}) without a solution better than the greedy "
                f"methods'; the {best_name} solution is used")
    fewest = len(chosen)
    conflicts = base_conflicts = None
    exact = False
    if avoid_conflicts:
        steps, conflicts, exact, base_conflicts = _conflict_plan(cands, feet, chosen)
        hoopings = _planned(cands, steps, feet)
    else:
        hoopings = _hoopings(cands, chosen, feet)
    report = SolveReport("garment", "mip" if use_mip else "greedy-fallback", sol.status,
                         bool(sol.optimal and use_mip), sol.mip_gap if use_mip else None,
                         bound, ffd_count, len(cands), time.perf_counter() - t0, time_limit_s,
                         note, fewest_hoopings=fewest, conflicts=conflicts,
                         conflicts_exact=exact, fewest_hoopings_conflicts=base_conflicts)
    return Grouping("garment", hoopings, report)
