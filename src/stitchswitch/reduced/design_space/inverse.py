"""Inverse design (paper, section 5): "given target deformation height, the system suggests
compatible parameter combinations".

1. Candidates: the grid designs of the design map (certified solves), with their switching
   force from the force model. The designer's bounds (largest diameter, smallest fill, force
   window) and the map's domain define the feasible set; its range of h is the achievable
   range, and a target outside it is refused with that range.
2. Selection: the mixed-integer program of ``inverse_mip`` picks up to ``count`` distinct
   alternatives (at most one per ``BIN_WIDTH_MM`` of diameter) of least mismatch.
3. Refinement: each pick keeps its diameter and its fill is moved continuously so that the
   map's interpolated h meets the target (and, with a radius target, both d and p are fitted
   to h and r_a by bounded least squares on the map).
4. Confirmation: every suggestion is solved directly; if its certified h misses the target by
   more than ``HEIGHT_TOL_MM`` the fill is corrected by a bracketed root search on direct
   solves. The reported keypoints are those of the direct solve, and a suggestion whose
   certified h still misses the target by more than ``HEIGHT_TOL_MM`` (the target is out of
   reach at that diameter under the bounds) is dropped: up to ``count`` suggestions remain.

Fabrication rules: ``admissible(d, p) -> str | None`` (for example the constraint check's
feature-size and hoop-fit rules, ``layout.check.design_point``, which this layer cannot import)
names the rule a design breaks. Grid designs that break one are left out of the selection (each
diameter bin keeps its ``PER_BIN`` cheapest admissible designs), and a refined suggestion that
breaks one is dropped. ``InverseResult.dropped`` says why each missing suggestion is missing, so
fewer than ``count`` suggestions always come with reasons.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq, least_squares

from stitchswitch.errors import InvalidInputError
from stitchswitch.reduced.design_space.design_map import FLAG_SMOOTH, KEYPOINTS, DesignMap
from stitchswitch.reduced.design_space.inverse_mip import select
from stitchswitch.reduced.model.params import Patch

HEIGHT_TOL_MM = 0.2
BIN_WIDTH_MM = 5.0
PER_BIN = 4


@dataclass(frozen=True)
class InverseTarget:
    height_mm: float
    radius_mm: float | None = None        # target r_a (the paper's "perceived radius r_d")
    max_diameter_mm: float | None = None
    min_fill: float | None = None
    force_range_N: tuple[float, float] | None = None
    count: int = 5

    def __post_init__(self):
        def positive(name, v):
            if v is not None and not (isinstance(v, (int, float)) and math.isfinite(v) and v > 0):
                raise InvalidInputError(f"{name}: {v!r} must be a positive number")
        positive("height_mm", self.height_mm)
        positive("radius_mm", self.radius_mm)
        positive("max_diameter_mm", self.max_diameter_mm)
        if self.min_fill is not None and not (0 < self.min_fill <= 1):
            raise InvalidInputError(f"min_fill: {self.min_fill!r} is outside (0, 1]")
        if self.force_range_N is not None:
            lo, hi = self.force_range_N
            if not (math.isfinite(lo) and math.isfinite(hi) and 0 <= lo <= hi):
                raise InvalidInputError(f"force_range_N: {self.force_range_N!r} must be 0 <= LO <= HI")
        if isinstance(self.count, bool) or not isinstance(self.count, int) or self.count < 1:
            raise InvalidInputError(f"count: {self.count!r} must be a positive integer")


@dataclass(frozen=True)
class Candidate:
    diameter_mm: float
    fill: float
    h_mm: float
    r_a_mm: float
    z_a_mm: float
    r_b_mm: float
    z_b_mm: float
    force_N: float
    force_extrapolated: bool | None       # outside the force data's design range (None: unknown)
    height_error_mm: float
    radius_error_mm: float | None
    residual: float
    converged: bool

    def as_dict(self) -> dict:
        """The fields, in order, with the diameter under the output's key ``d_mm``."""
        out = dict(self.__dict__)
        return {"d_mm": out.pop("diameter_mm"), **out}


def _default_force():
    """The default force model's predictor, and its extrapolation test."""
    from stitchswitch.reduced.design_space.force_model import default_force_fit

    fit = default_force_fit()
    return fit.model.predict, fit.extrapolates


def _bounds_text(target: InverseTarget, dmap: DesignMap) -> str:
    parts = [dmap.domain_text()]
    if target.max_diameter_mm is not None:
        parts.append(f"d <= {target.max_diameter_mm:g} mm")
    if target.min_fill is not None:
        parts.append(f"fill >= {target.min_fill:g}")
    if target.force_range_N is not None:
        parts.append(f"force in [{target.force_range_N[0]:g}, {target.force_range_N[1]:g}] N")
    return ", ".join(parts)


@dataclass(frozen=True)
class InverseResult:
    candidates: list            # Candidate, best first
    achievable_h_mm: tuple      # range of h over the feasible grid designs
    selection: object           # inverse_mip.Selection: status, objective, solve time, gap
    dropped: tuple = ()         # why designs were left out: one sentence each


def _admissible_per_bin(idx, bins, cost, d, p, admissible):
    """The ``PER_BIN`` cheapest designs of each bin that ``admissible`` accepts (all of them
    without it), and the rules that cost designs (rule text -> count)."""
    order = np.lexsort((cost[idx], bins))
    if admissible is None:
        rank = np.arange(order.size) - np.searchsorted(bins[order], bins[order])
        return np.sort(idx[order[rank < PER_BIN]]), {}
    keep, broken, taken = [], {}, {}
    for j in order:
        b = int(bins[j])
        if taken.get(b, 0) >= PER_BIN:
            continue
        why = admissible(float(d[idx[j]]), float(p[idx[j]]))
        if why is None:
            keep.append(idx[j])
            taken[b] = taken.get(b, 0) + 1
        else:
            broken[why] = broken.get(why, 0) + 1
    return np.sort(np.asarray(keep, dtype=int)), broken


def inverse_design(target: InverseTarget, dmap: DesignMap | None = None,
                   force=None, admissible=None) -> InverseResult:
    """Up to ``target.count`` confirmed designs, best first (see the module docstring);
    ``admissible(d, p)``: the fabrication rule a design breaks, or None."""
    from stitchswitch.reduced.design_space.cache import default_map

    dmap = dmap or default_map()
    extrapolates = None
    if force is None:
        force, extrapolates = _default_force()
    D, P = np.meshgrid(dmap.diameter_mm, dmap.fill, indexing="ij")
    d, p = D.ravel(), P.ravel()
    F = np.asarray(force(d, p), dtype=float)
    h, ra = dmap.h_mm.ravel(), dmap.r_a_mm.ravel()
    d_max = target.max_diameter_mm if target.max_diameter_mm is not None else np.inf
    p_min = target.min_fill if target.min_fill is not None else -np.inf
    f_lo, f_hi = target.force_range_N if target.force_range_N is not None else (-np.inf, np.inf)
    usable = dmap.converged.ravel() & (dmap.flags.ravel() == FLAG_SMOOTH)
    feasible = usable & (d <= d_max) & (p >= p_min) & (F >= f_lo) & (F <= f_hi)
    if not feasible.any():
        raise InvalidInputError(f"no design satisfies the constraints ({_bounds_text(target, dmap)})")
    h_lo, h_hi = h[feasible].min(), h[feasible].max()
    if not h_lo - HEIGHT_TOL_MM <= target.height_mm <= h_hi + HEIGHT_TOL_MM:
        raise InvalidInputError(
            f"height {target.height_mm:g} mm is not achievable: under the constraints "
            f"({_bounds_text(target, dmap)}) h ranges from {h_lo:.2f} to {h_hi:.2f} mm")
    cost = np.abs(h - target.height_mm) / target.height_mm
    if target.radius_mm is not None:
        cost = cost + np.abs(ra - target.radius_mm) / target.radius_mm
    # presolve: at most one design per diameter bin is chosen, so only the PER_BIN cheapest
    # feasible designs of each bin can be in the optimum; the program keeps those
    idx = np.nonzero(feasible)[0]
    bins = np.floor((d[idx] - dmap.diameter_mm[0]) / BIN_WIDTH_MM).astype(int)
    idx, broken = _admissible_per_bin(idx, bins, cost, d, p, admissible)
    dropped = [f"{n} grid design(s) near the target left out: {why}"
               for why, n in sorted(broken.items())]
    if not len(idx):
        raise InvalidInputError(
            f"no design under the constraints ({_bounds_text(target, dmap)}) passes the "
            "fabrication rules: " + "; ".join(dropped))
    choice = select(cost[idx], d[idx], p[idx], F[idx], count=target.count,
                    bin_width_mm=BIN_WIDTH_MM, bin_origin_mm=dmap.diameter_mm[0],
                    d_max=d_max, p_min=p_min, force_range=(f_lo, f_hi))
    picks = idx[choice.indices]
    out = []
    for k in picks:
        dd, pp = _refine(dmap, target, d[k], p[k], d_max, p_min)
        cand = _confirm(dmap, target, dd, pp, force, p_min, extrapolates)
        at = f"d = {cand.diameter_mm:.2f} mm, fill {cand.fill:.3f}"
        if cand.force_N < f_lo - 1e-12 or cand.force_N > f_hi + 1e-12:
            dropped.append(f"{at}: force {cand.force_N:.3f} N outside the window")
            continue
        if abs(cand.height_error_mm) > HEIGHT_TOL_MM or not cand.converged:
            # the target is not reachable from this pick's diameter
            dropped.append(f"{at}: certified h misses the target by "
                           f"{abs(cand.height_error_mm):.2f} mm" if cand.converged
                           else f"{at}: the direct solve did not converge")
            continue
        why = None if admissible is None else admissible(cand.diameter_mm, cand.fill)
        if why is not None:
            dropped.append(f"{at} (refined): {why}")
            continue
        out.append(cand)
    out.sort(key=lambda c: abs(c.height_error_mm) + abs(c.radius_error_mm or 0.0))
    distinct = []
    for c in out:               # refinements from neighbouring bins may meet at one design
        if all(abs(c.diameter_mm - o.diameter_mm) > 0.5 or abs(c.fill - o.fill) > 0.005 for o in distinct):
            distinct.append(c)
    if len(distinct) < len(out):
        dropped.append(f"{len(out) - len(distinct)} refinement(s) met another suggestion")
    if len(picks) < target.count:
        dropped.append(f"the selection found {len(picks)} distinct diameter bin(s) of "
                       f"{BIN_WIDTH_MM:g} mm under the bounds, fewer than the {target.count} asked")
    return InverseResult(distinct, (float(h_lo), float(h_hi)), choice, tuple(dropped))


def _refine(dmap, target, d0, p0, d_max, p_min):
    """Continuous design near the grid pick that meets the target on the map."""
    p_lo = max(dmap.fill[0], p_min if np.isfinite(p_min) else dmap.fill[0])
    d_hi = min(dmap.diameter_mm[-1], d_max)
    if target.radius_mm is not None:
        def res(x):
            q = dmap.query(x[0], x[1])
            return [(q.h_mm[0] - target.height_mm) / target.height_mm,
                    (q.r_a_mm[0] - target.radius_mm) / target.radius_mm]
        # stay in the pick's diameter bin, so that the alternatives stay distinct
        lo = [max(dmap.diameter_mm[0], d0 - BIN_WIDTH_MM / 2), p_lo]
        hi = [min(d_hi, d0 + BIN_WIDTH_MM / 2), dmap.fill[-1]]
        sol = least_squares(res, np.clip([d0, p0], lo, hi), bounds=(lo, hi))
        return float(sol.x[0]), float(sol.x[1])
    f = lambda pp: dmap.query(d0, pp).h_mm[0] - target.height_mm  # noqa: E731
    a, b = max(p_lo, p0 - 0.01), min(dmap.fill[-1], p0 + 0.01)
    if f(a) * f(b) < 0:
        return float(d0), float(brentq(f, a, b, xtol=1e-6))
    return float(d0), float(p0)


def _confirm(dmap, target, d, p, force, p_min, extrapolates=None) -> Candidate:
    from stitchswitch.reduced.solvers.solve import solve

    material = dmap.material
    sol = solve(Patch(d, p), material)
    if target.radius_mm is None and abs(sol.keypoints.h_mm - target.height_mm) > HEIGHT_TOL_MM:
        # correct the fill on direct solves, bracketed within +-0.03 of the map's estimate
        f = lambda pp: solve(Patch(d, pp), material).keypoints.h_mm - target.height_mm  # noqa: E731
        lo = max(p - 0.03, p_min if np.isfinite(p_min) else 0.05, 0.05)
        hi = min(p + 0.03, 1.0)
        if f(lo) * f(hi) < 0:
            p = float(brentq(f, lo, hi, xtol=1e-5))
            sol = solve(Patch(d, p), material)
    kp = sol.keypoints
    return Candidate(
        diameter_mm=float(d), fill=float(p), **{name: float(getattr(kp, name)) for name in KEYPOINTS},
        force_N=float(np.asarray(force(np.array([d]), np.array([p])))[0]),
        force_extrapolated=None if extrapolates is None else bool(extrapolates(d, p)),
        height_error_mm=float(kp.h_mm - target.height_mm),
        radius_error_mm=None if target.radius_mm is None else float(kp.r_a_mm - target.radius_mm),
        residual=float(sol.residual), converged=bool(sol.converged))
