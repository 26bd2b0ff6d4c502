"""Free mode: patches stitched on separate stretched fabric, to be sewn onto the garment later.

Pack the footprints (discs of diameter d, at least ``spacing_mm`` apart) into as few hoops as
possible. A disc must lie in the field minus the margin; spacing to the margin line is not
required. Equivalently, discs of radius d/2 + s/2 must not overlap inside the usable area grown
by s/2 on every side: that is the container ``circle_packing`` fills.

Formulation (two stages, documented in docs/fabrication.md):

1. *Hoop loads* (columns): sets of patches with positions that fit one hoop type, produced by
   first-fit decreasing opening every hoop type (``greedy``; with and without shrinking
   each hoop to the smallest type that holds its patches) and by column generation: the LP
   relaxation of stage 2 (cvxpy + HiGHS) gives dual prices pi_i of the patches; for every hoop
   type a load is built greedily in the order of pi_i / area_i (and of pi_i), and added when
   its reduced cost w1 + w3 - sum pi_i is negative; repeated until no load improves, the LP
   value stalls (it fell by less than 0.02 hoopings over 3 rounds), or 25 rounds or 60 % of the
   time limit are used (the report says when the time cut it short: only then can the result
   depend on the machine's speed). Every load is made maximal by adding whatever else still
   fits (a subset of a load is a load too). When the proven lower bound below already equals
   the first-fit count, column generation is skipped: no grouping can use fewer hoops.
2. *Set cover MIP* over the loads (``mip``): fewest hoopings, then fewest hoop types, then
   smaller hoops (w3 = the hoop's rank by field area). A patch held by two chosen loads stays in
   the larger one. Each hooping's group of patches is centred in the hoop.

The MIP is exact over the generated loads, not over all packings, so its "optimal" means
optimal over those loads. The report adds a proven lower bound on the hoopings of any packing:
the larger of ceil(sum of disc areas (d + s)^2 pi / 4 over the roomiest grown container) and
the size of a set of patches of which no two fit one hoop together (greedy clique; two discs
fit a W x H container iff each fits alone and (W - a - b)^2 + (H - a - b)^2 >= (a + b)^2 for
radii a, b). First-fit decreasing (opening the hoop with the largest short side, then the
largest area) is always among the loads, so the result never has more hoopings than it.
"""
from __future__ import annotations

import logging
import math
import time
import warnings

import numpy as np

from stitchswitch import native_output
from stitchswitch.errors import InvalidInputError
from stitchswitch.layout.fabrication.grouping import circle_packing as cpk
from stitchswitch.layout.fabrication.grouping import greedy
from stitchswitch.layout.fabrication.grouping.mip import solve_cover
from stitchswitch.layout.fabrication.grouping.result import Grouping, Hooping, SolveReport

log = logging.getLogger(__name__)

BUDGET = 0.6        # share of the time limit for generating loads
CG_ROUNDS = 25      # column generation: at most this many LP rounds ...
TAIL_ROUNDS = 3     # ... and stop when the LP value fell by less than
TAIL_DROP = 0.02    # ... this many hoopings over the last TAIL_ROUNDS rounds


def containers(hoops, spacing_mm: float) -> list[tuple[float, float]]:
    return [(h.usable_mm()[0] + spacing_mm, h.usable_mm()[1] + spacing_mm) for h in hoops]


def _check(feet, hoops) -> None:
    best = max(min(h.usable_mm()) for h in hoops)
    for f in feet:
        if f.diameter_mm > best + 1e-9:
            big = max(hoops, key=lambda h: (min(h.usable_mm()), h.area_mm2))
            raise InvalidInputError(
                f"patch {f.id!r}: its {f.diameter_mm:g} mm footprint on the stretched fabric fits "
                f"no hoop; the roomiest is {big} with {big.usable_mm()[0]:g} x "
                f"{big.usable_mm()[1]:g} mm inside its {big.margin_mm:g} mm margin")


def pair_fits(a: float, b: float, w: float, h: float) -> bool:
    if 2 * max(a, b) > min(w, h) + 1e-9:
        return False
    dx, dy = max(w - a - b, 0.0), max(h - a - b, 0.0)
    return dx * dx + dy * dy >= (a + b) ** 2 - 1e-9


def lower_bound(radii, conts) -> int:
    """Proven lower bound on the number of hoops (see the module docstring)."""
    radii = np.asarray(radii, dtype=float)
    area = math.ceil(float(np.sum(np.pi * radii ** 2)) / max(w * h for w, h in conts) - 1e-9)
    clique: list[int] = []
    for i in np.lexsort((np.arange(len(radii)), -radii)):
        if all(not any(pair_fits(radii[i], radii[j], w, h) for w, h in conts) for j in clique):
            clique.append(int(i))
    return max(1, area, len(clique))


class _Loads:
    """Deduplicated hoop loads: (hoop type, sorted members) -> centres."""

    def __init__(self, n: int):
        self.n = n
        self.keys: dict[tuple, int] = {}
        self.items: list[tuple[int, tuple[int, ...], np.ndarray]] = []

    def add(self, t: int, members, centres) -> tuple[int, bool]:
        """(index of the load, whether it is new)."""
        order = np.argsort(members, kind="stable")
        members = tuple(int(members[k]) for k in order)
        key = (t, members)
        if key in self.keys:
            return self.keys[key], False
        self.keys[key] = len(self.items)
        self.items.append((t, members, np.asarray(centres, dtype=float)[order]))
        return self.keys[key], True

    def holds(self) -> np.ndarray:
        out = np.zeros((len(self.items), self.n), dtype=bool)
        for j, (_, members, _) in enumerate(self.items):
            out[j, list(members)] = True
        return out


def _maximal(members, centres, radii, cont, order):
    """Add every other patch (in ``order``) that still fits the load."""
    members, centres = list(members), np.asarray(centres, dtype=float).reshape(-1, 2)
    have = set(members)
    room = cont[0] * cont[1] - float(np.sum(np.pi * radii[members] ** 2))
    for i in order:
        if i in have or np.pi * radii[i] ** 2 > room:
            continue
        p = cpk.pack([radii[i]], cont[0], cont[1], centres, radii[members])
        if p is not None:
            members.append(int(i))
            centres = np.vstack([centres, p])
            have.add(int(i))
            room -= np.pi * radii[i] ** 2
    return members, centres


def _greedy_load(order, radii, cont):
    members, centres = [], np.zeros((0, 2))
    for i in order:
        p = cpk.pack([radii[i]], cont[0], cont[1], centres, radii[members])
        if p is not None:
            members.append(int(i))
            centres = np.vstack([centres, p])
    return members, centres


def _add_solution(loads, sol, radii, conts, fill_order) -> list[int]:
    """Add a greedy solution's loads (made maximal); their indices."""
    out = []
    for t, members, centres in sol:
        m, c = _maximal(members, centres, radii, conts[t], fill_order)
        out.append(loads.add(t, m, c)[0])
    return out


def _lp_duals(holds, cost):
    import cvxpy as cp
    x = cp.Variable(holds.shape[0])
    cover = holds.T.astype(float) @ x >= 1
    prob = cp.Problem(cp.Minimize(cost @ x), [cover, x >= 0, x <= 1])
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", UserWarning)
        with native_output.to_logger(log):
            prob.solve(solver=cp.HIGHS)
    if prob.status not in (cp.OPTIMAL, cp.OPTIMAL_INACCURATE) or cover.dual_value is None:
        return None, None
    return np.maximum(np.asarray(cover.dual_value, dtype=float), 0.0), float(prob.value)


def _column_generation(loads, radii, conts, cost_of, w1, t0, budget) -> bool:
    """Add priced loads until nothing improves or the LP value stalls (see the module
    docstring). Returns True if the time budget cut it short."""
    n = len(radii)
    area = np.pi * radii ** 2
    lp_values: list[float] = []
    for _ in range(CG_ROUNDS):
        if budget is not None and time.perf_counter() - t0 > budget:
            return True
        cost = np.array([cost_of(t) for t, _, _ in loads.items], dtype=float)
        pi, value = _lp_duals(loads.holds(), cost)
        if pi is None:
            return False
        lp_values.append(value)
        if len(lp_values) > TAIL_ROUNDS and lp_values[-TAIL_ROUNDS - 1] - value < TAIL_DROP * w1:
            return False                         # tailing off
        added = 0
        for t, cont in enumerate(conts):
            fit = [i for i in range(n) if 2 * radii[i] <= min(cont) + 1e-9 and pi[i] > 1e-9]
            for score in (pi / area, pi):
                order = sorted(fit, key=lambda i: (-score[i], -radii[i], i))
                m, c = _greedy_load(order, radii, cont)
                if sum(pi[i] for i in m) > cost_of(t) + 1e-6:
                    m, c = _maximal(m, c, radii, cont, list(np.lexsort((np.arange(n), -radii))))
                    added += loads.add(t, m, c)[1]
        if not added:
            return False
    return False


def group_free(feet, hoops, spacing_mm: float = 10.0, time_limit_s: float | None = None
               ) -> Grouping:
    """Hoopings of free-standing patches (see the module docstring)."""
    if not (math.isfinite(spacing_mm) and spacing_mm >= 0):
        raise InvalidInputError(f"spacing {spacing_mm!r} mm must be a finite number >= 0")
    t0 = time.perf_counter()
    feet, hoops = tuple(feet), tuple(hoops)
    _check(feet, hoops)
    n = len(feet)
    radii = np.array([f.diameter_mm / 2 + spacing_mm / 2 for f in feet])
    conts = containers(hoops, spacing_mm)
    area_rank = np.argsort(np.argsort([h.area_mm2 for h in hoops], kind="stable"), kind="stable")
    w2 = n * (len(hoops) - 1) + 1
    w1 = len(hoops) * w2 + n * (len(hoops) - 1) + 1
    cost_of = lambda t: w1 + int(area_rank[t])  # noqa: E731
    by_size = list(np.lexsort((np.arange(n), -radii)))
    loads = _Loads(n)
    roomy = max(range(len(hoops)), key=lambda t: (min(conts[t]), conts[t][0] * conts[t][1]))
    ffd = greedy.first_fit_decreasing_free(radii, conts, roomy)
    greedy_sols = [_add_solution(loads, ffd, radii, conts, by_size)]
    for t in range(len(hoops)):
        if all(2 * r <= min(conts[t]) + 1e-9 for r in radii):
            for shrink in (True, False):        # unshrunk: loads of one hoop type only
                sol = greedy.first_fit_decreasing_free(radii, conts, t, shrink)
                greedy_sols.append(_add_solution(loads, sol, radii, conts, by_size))
    bound = lower_bound(radii, conts)
    cut = False
    if bound < min(len(js) for js in greedy_sols):          # else first fit is proven optimal
        budget = None if time_limit_s is None else BUDGET * time_limit_s
        cut = _column_generation(loads, radii, conts, cost_of, w1, t0, budget)
    kind = np.array([t for t, _, _ in loads.items])
    cost = np.array([cost_of(t) for t in kind])
    left = None if time_limit_s is None else max(0.05, time_limit_s - (time.perf_counter() - t0))
    sol = solve_cover(loads.holds(), cost, kind, w2, left, min_count=bound)

    def key(js):
        return (len(js), len({int(kind[j]) for j in js}), int(sum(area_rank[kind[j]] for j in js)))

    best_greedy = min(greedy_sols, key=key)
    use_mip = sol.chosen is not None and key(list(sol.chosen)) <= key(best_greedy)
    chosen = list(sol.chosen) if use_mip else best_greedy
    if use_mip:
        note = (f"optimal over {len(loads.items)} generated hoop loads" if sol.optimal else
                f"HiGHS stopped ({sol.status}) with a solution at least as good as first-fit "
                "decreasing")
    else:
        note = (f"HiGHS stopped ({sol.status}) without a solution better than first-fit "
                "decreasing; that solution is used")
    if cut:
        note += "; load generation was cut short by the time limit"
    report = SolveReport("free", "mip" if use_mip else "greedy-fallback", sol.status,
                         bool(sol.optimal and use_mip), sol.mip_gap if use_mip else None,
                         bound, len(ffd), len(loads.items), time.perf_counter() - t0,
                         time_limit_s, note)
    return Grouping("free", _hoopings(loads, chosen, feet, hoops), report)


def _hoopings(loads, chosen, feet, hoops) -> tuple[Hooping, ...]:
    taken: set[int] = set()
    out = []
    for j in sorted(chosen, key=lambda j: (-len(loads.items[j][1]), j)):
        t, members, centres = loads.items[j]
        keep = [k for k, i in enumerate(members) if i not in taken]
        if not keep:
            continue
        taken.update(members[k] for k in keep)
        rad = np.array([feet[members[k]].radius_mm for k in keep])
        pos = centres[keep]
        lo, hi = (pos - rad[:, None]).min(axis=0), (pos + rad[:, None]).max(axis=0)
        pos = pos - (lo + hi) / 2            # the group centred in the hoop
        out.append(Hooping(hoops[t], 0, tuple(feet[members[k]].id for k in keep),
                           tuple((float(a), float(b)) for a, b in pos)))
    return tuple(out)
