"""Weighted set cover with a per-type charge, as a mixed-integer program (cvxpy + HiGHS).

Both hoop-grouping modes reduce to it: candidate hoopings c (a hoop type, a placement and the
patches it can hold) are columns, patches are rows. With binary x_c (candidate used) and y_t
(hoop type t used):

    minimize    sum_c cost_c x_c + type_cost * sum_t y_t
    subject to  sum_{c holds i} x_c >= 1      for every patch i   (every patch in some hooping)
                x_c <= y_{type(c)}            for every candidate c
                x, y binary.

The costs are integers (the callers weight hoopings, hoop types and a tie-breaker so that one
hooping more always costs more than any saving in the lower objectives), so HiGHS runs with
``mip_abs_gap`` just under 1 and a zero relative gap: "optimal" means exactly optimal. A patch
covered twice is later kept in one hooping only. The solver call follows
``reduced.design_space.inverse_mip``: ``problem.solve(solver=cp.HIGHS, ...)``, status checked, the gap read
from ``solver_stats.extra_stats``; ``time_limit_s`` goes to HiGHS's ``time_limit``.
"""
from __future__ import annotations

import logging
import time
import warnings
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from stitchswitch import native_output
from stitchswitch.errors import StitchSwitchError

log = logging.getLogger(__name__)

@dataclass(frozen=True)
class CoverSolution:
    chosen: np.ndarray | None   # candidate indices (ascending); None: HiGHS found no solution
    status: str                 # cvxpy status ("optimal", "user_limit", ...)
    optimal: bool
    mip_gap: float | None
    dual_bound: float | None    # HiGHS's lower bound on the objective
    objective: float | None
    solve_s: float


def _info(problem):
    stats = getattr(problem, "solver_stats", None)
    return getattr(stats, "extra_stats", None) if stats else None


def _attr(info, name):
    if info is None:
        return None
    v = getattr(info, name, None)
    if v is None and isinstance(info, dict):
        v = info.get(name)
    return v


def solve_cover(cover: np.ndarray, cost: np.ndarray, kind: np.ndarray, type_cost: float,
                time_limit_s: float | None = None, min_count: int = 1) -> CoverSolution:
    """Solve the program above. ``cover``: (m, n) bool, candidate c holds patch i; ``cost``:
    (m,) integer costs; ``kind``: (m,) hoop-type index of each candidate. Every patch must be
    held by at least one candidate (the caller checks and names the patch otherwise).
    ``min_count``: a proven lower bound on the number of candidates, added as the valid cut
    sum_c x_c >= min_count (it spares HiGHS proving it by branching)."""
    import cvxpy as cp

    cover = np.asarray(cover, dtype=bool)
    m, n = cover.shape
    kinds, kind_idx = np.unique(np.asarray(kind), return_inverse=True)
    a = sp.csr_matrix(cover.T.astype(float))                       # (n, m)
    k = sp.csr_matrix((np.ones(m), (np.arange(m), kind_idx)), shape=(m, len(kinds)))
    x = cp.Variable(m, boolean=True)
    y = cp.Variable(len(kinds), boolean=True)
    problem = cp.Problem(cp.Minimize(np.asarray(cost, float) @ x + float(type_cost) * cp.sum(y)),
                         [a @ x >= 1, x <= k @ y, cp.sum(x) >= int(min_count)])
    opts = {"mip_rel_gap": 0.0, "mip_abs_gap": 0.999}
    if time_limit_s is not None:
        opts["time_limit"] = float(time_limit_s)
    t = time.perf_counter()
    try:
        with warnings.catch_warnings():     # "may be inaccurate" at a time limit: reported
            warnings.simplefilter("ignore", UserWarning)
            with native_output.to_logger(log):
                problem.solve(solver=cp.HIGHS, **opts)
    except cp.error.SolverError as exc:
        raise StitchSwitchError(f"hoop grouping: HiGHS failed ({exc})") from None
    seconds = time.perf_counter() - t
    info = _info(problem)
    status = str(problem.status)
    has = (status in (cp.OPTIMAL, cp.OPTIMAL_INACCURATE, cp.USER_LIMIT) and x.value is not None
           and _attr(info, "primal_solution_status") not in (0,))
    chosen = None
    if has:
        xv = np.asarray(x.value, dtype=float)
        chosen = np.flatnonzero(xv > 0.5)
        held = cover[chosen].any(axis=0) if len(chosen) else np.zeros(n, dtype=bool)
        if not held.all():
            chosen = None                      # an unusable incumbent: treat as none
    elif status not in (cp.USER_LIMIT,):
        raise StitchSwitchError(f"hoop grouping: HiGHS returned status {status!r}")
    gap = _attr(info, "mip_gap")
    bound = _attr(info, "mip_dual_bound")
    return CoverSolution(chosen, status, status == cp.OPTIMAL and chosen is not None,
                         None if gap is None or chosen is None else float(gap),
                         None if bound is None or not np.isfinite(bound) else float(bound),
                         None if chosen is None else float(problem.value), seconds)
