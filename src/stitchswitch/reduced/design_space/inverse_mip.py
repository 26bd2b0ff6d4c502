"""The selection step of inverse design, stated as a mixed-integer program (cvxpy + HiGHS).

Given candidate designs k (the grid points of a design map) with attributes d_k, p_k, F_k
(switching force) and a mismatch cost c_k (distance of their keypoints to the target), choose
binary x_k:

    minimize    sum_k c_k x_k
    subject to  sum_k x_k = K                                   (K suggestions)
                sum_{k in bin b} x_k <= 1   for every diameter bin b   (distinct alternatives)
                (d_k - d_max) x_k <= 0,  (p_min - p_k) x_k <= 0         (designer's bounds)
                (F_lo - F_k) x_k <= 0,  (F_k - F_hi) x_k <= 0           (force window)
                x_k in {0, 1}.

The bins make the suggestions distinct designs spread over the diameters, rather than K
copies of one design at neighbouring grid points. HiGHS solves it through cvxpy; the status is
checked and the optimality gap reported.
"""
from __future__ import annotations

import logging
import time
from dataclasses import dataclass

import numpy as np

from stitchswitch import native_output
from stitchswitch.errors import StitchSwitchError

log = logging.getLogger(__name__)

@dataclass(frozen=True)
class Selection:
    indices: np.ndarray        # chosen candidates, best (lowest cost) first
    objective: float
    status: str
    solve_s: float
    mip_gap: float | None


def select(cost: np.ndarray, diameter_mm: np.ndarray, fill: np.ndarray, force_N: np.ndarray, *,
           count: int, bin_width_mm: float, bin_origin_mm: float = 0.0,
           d_max: float = np.inf, p_min: float = -np.inf,
           force_range=(-np.inf, np.inf)) -> Selection:
    """Solve the program above; ``count`` is reduced to the number of bins that hold a
    feasible candidate. Raises if the solver fails."""
    import cvxpy as cp

    n = cost.size
    bins = np.floor((diameter_mm - bin_origin_mm) / bin_width_mm).astype(int)
    lo, hi = force_range
    feasible = (diameter_mm <= d_max) & (fill >= p_min) & (force_N >= lo) & (force_N <= hi)
    k = min(count, np.unique(bins[feasible]).size)
    if k == 0:
        return Selection(np.array([], dtype=int), 0.0, "infeasible", 0.0, None)
    x = cp.Variable(n, boolean=True)
    member = np.zeros((bins.max() + 1, n))
    member[bins, np.arange(n)] = 1.0
    big = lambda v: np.where(np.isfinite(v), v, 0.0)  # noqa: E731 - an infinite bound is no bound
    constraints = [cp.sum(x) == k, member @ x <= 1]
    if np.isfinite(d_max):
        constraints.append(cp.multiply(diameter_mm - d_max, x) <= 0)
    if np.isfinite(p_min):
        constraints.append(cp.multiply(p_min - fill, x) <= 0)
    if np.isfinite(lo):
        constraints.append(cp.multiply(big(lo) - force_N, x) <= 0)
    if np.isfinite(hi):
        constraints.append(cp.multiply(force_N - big(hi), x) <= 0)
    problem = cp.Problem(cp.Minimize(cost @ x), constraints)
    t = time.perf_counter()
    with native_output.to_logger(log):
        problem.solve(solver=cp.HIGHS)
    seconds = time.perf_counter() - t
    if problem.status not in (cp.OPTIMAL, cp.OPTIMAL_INACCURATE) or x.value is None:
        raise StitchSwitchError(f"candidate selection: HiGHS returned status {problem.status!r}")
    chosen = np.nonzero(x.value > 0.5)[0]
    chosen = chosen[np.argsort(cost[chosen], kind="stable")]
    gap = None
    stats = getattr(problem, "solver_stats", None)
    extra = getattr(stats, "extra_stats", None) if stats else None
    if extra is not None:
        gap = getattr(extra, "mip_gap", None)
        if gap is None and isinstance(extra, dict):
            gap = extra.get("mip_gap")
    return Selection(chosen, float(problem.value), str(problem.status), seconds,
                     None if gap is None else float(gap))
