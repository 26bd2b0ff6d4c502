"""Calibration of the material by differential evolution (paper, section 4), then a local polish.

The objective is the paper's: the mean squared error (mm^2) over the five keypoints
(h, r_a, z_a, r_b, z_b) of the training rows, each predicted by a certified solve.

Parameters (``PARAMS``): the paper's seven coefficients and the parameters of the model that
move the keypoints by more than the measurement noise: the compressive stiffness ratios of the
stitched mats ``c_emb`` and of the bare knit ``c_fab``, the jamming stretch ``jam``, the jammed
knit's stiffness ratio ``c_jam`` and the hardening limit ``gamma_mm`` (docs/model.md,
"Sensitivity").

Identifiability. The energy is homogeneous of degree one in the seven coefficients (c_emb and
c_fab are ratios to k_r), so scaling all of them by one factor leaves every equilibrium
unchanged: **the overall scale is not identifiable from shapes**. The fit therefore holds
``SCALE_PARAM`` (k_theta_fab) at its starting value and fits the others relative to it.
Weaker correlations are measured, not assumed: at the optimum, the Jacobian of the training
keypoints with respect to the search coordinates gives singular values, and directions whose
singular value is below ``WEAK_RATIO`` times the largest are reported as poorly identified.

Search space (documented bounds, ``BOUNDS``): log10 of the stiffnesses, c_emb, c_fab, c_jam
and gamma_mm; w_log and jam on a linear scale (w_log may be 0). c_fab's lower bound 1e-3 keeps the
bare knit's slack segments from being nearly free, which makes Newton's method several times
slower (docs/model.md, "Compression as physics").

The population is updated once per generation (scipy's "deferred" updating) on one worker as on
many, so the fit does not depend on the number of workers (tests/test_calibration.py).

Termination. scipy stops the search when the standard deviation of the population's objective
values is at most ``tol`` times their mean, or after ``maxiter`` generations. ``DE_TOL`` (0.2)
is set from convergence traces on the synthetic reference dataset (docs/calibration.md,
"Termination", ``scripts/trace_calibration.py``): with popsize 10 and seeds 0, 1 and 2 the
spread falls below 20 % of the mean after 9-12 generations, and the polished best member fits
the training rows and predicts the validation rows as well as after 30 generations (train MSE
within 0.02 mm^2, validation MAE within 0.03 mm); later generations improve the search's best
member by a few hundredths of a mm^2, which the polish makes up.

Two resolutions. The search runs at ``SEARCH_NODES`` nodes (``search_material``: the same
domain and physics, a coarser spacing), where the 25 calibration designs solve in about 40 %
of the time they take at the default 300 nodes, and their keypoints move by 0.01-0.15 mm on
average between the two (at most 0.6 mm, in z_b), under the measurement noise. The polish, the
reported MSE and the identifiability use the start material's own resolution, so the result is
the fine model's: the polish runs first at the search resolution (cheap, to its minimum), then
at the fine one, where only the small shift between the two minima is left to travel.

Polish. Differential evolution ends near, not at, a minimum. From its best member a bounded
trust-region least-squares fit of the keypoint residuals (``scipy.optimize.least_squares``,
at most ``POLISH_EVALUATIONS`` objective evaluations) takes the last step; its result is kept
only if it lowers the MSE.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass, field

import numpy as np

from stitchswitch.errors import InvalidInputError
from stitchswitch.reduced.model.params import Material, Patch

#: The seven coefficients of the paper.
COEFFICIENTS = ("w_b_emb", "w_b_fab", "k_r_emb", "k_r_fab", "k_theta_emb", "k_theta_fab", "w_log")
#: Every parameter calibration may fit.
PARAMS = COEFFICIENTS + ("c_emb", "c_fab", "jam", "c_jam", "gamma_mm")
#: Held fixed: the overall scale of the energy is not identifiable.
SCALE_PARAM = "k_theta_fab"
#: Bounds of the free parameters: (low, high, scale) with scale "log" (log10) or "linear".
BOUNDS = {
    "w_b_emb": (0.1, 100.0, "log"),
    "w_b_fab": (0.02, 20.0, "log"),
    "k_r_emb": (0.02, 10.0, "log"),
    "k_r_fab": (0.005, 5.0, "log"),
    "k_theta_emb": (0.05, 10.0, "log"),
    "w_log": (0.0, 2.0, "linear"),
    "c_emb": (1e-4, 0.3, "log"),
    "c_fab": (1e-3, 0.1, "log"),
    "jam": (0.1, 0.8, "linear"),
    "c_jam": (0.1, 10.0, "log"),
    "gamma_mm": (0.5, 30.0, "log"),
}
#: What ``calibrate`` fits unless told otherwise: every parameter but the scale.
DEFAULT_FREE = tuple(n for n in PARAMS if n != SCALE_PARAM)
#: Differential evolution's termination tolerance (module docstring, "Termination").
DE_TOL = 0.2
#: Budget of the local polish, in objective evaluations.
POLISH_EVALUATIONS = 60
#: Nodes of the differential-evolution search (module docstring, "Two resolutions").
SEARCH_NODES = 150
#: Newton budget of the search's solves: a solve that needs more counts as not certified (the
#: objective's penalty). Such solves come from random members of the first generations (6 %
#: of them over the bounds; at most 48 iterations at the default and the synthetic true
#: material); the budget keeps them from costing 500 iterations and the release continuation.
SEARCH_MAX_ITER = 150
WEAK_RATIO = 1e-2
#: Penalty (mm^2) added per training design whose solve is not certified.
UNCONVERGED_PENALTY = 100.0


def _to_x(values: dict, free) -> np.ndarray:
    return np.array([math.log10(values[n]) if BOUNDS[n][2] == "log" else values[n] for n in free])


def _from_x(x, free, base: Material) -> Material:
    changes = {n: (10.0 ** v if BOUNDS[n][2] == "log" else float(v)) for n, v in zip(free, x)}
    return base.replace(**changes)


def _search_bounds(free):
    return [((math.log10(BOUNDS[n][0]), math.log10(BOUNDS[n][1])) if BOUNDS[n][2] == "log"
             else BOUNDS[n][:2]) for n in free]


def design_keypoints(material: Material, design, max_iter: int | None = None) -> tuple[tuple, bool]:
    """The five keypoints of one design (d, p) and whether its solve is certified."""
    from stitchswitch.reduced.solvers.solve import solve

    sol = solve(Patch(*design), material, max_iter=max_iter)
    kp = sol.keypoints
    return (kp.h_mm, kp.r_a_mm, kp.z_a_mm, kp.r_b_mm, kp.z_b_mm), sol.certified


@dataclass(frozen=True)
class _DesignTask:
    """Picklable ``design -> design_keypoints(material, design, max_iter)``."""

    material: Material
    max_iter: int | None

    def __call__(self, design):
        return design_keypoints(self.material, design, self.max_iter)


def predict_keypoints(material: Material, designs, max_iter: int | None = None,
                      executor=None) -> tuple[np.ndarray, int]:
    """(n, 5) keypoints of ``designs`` [(d, p), ...] and how many solves were not certified
    (``max_iter``: the solves' Newton budget, default ``solve``'s). ``executor``: a map-like
    (``stitchswitch.executor``) that solves the designs in parallel; the result is the same."""
    task = _DesignTask(material, max_iter)
    results = list(executor.map(task, list(designs))) if executor is not None else map(task, designs)
    out, bad = [], 0
    for kp, certified in results:
        out.append(kp)
        bad += not certified
    return np.array(out), bad


@dataclass(frozen=True)
class Objective:
    """Picklable objective: x (search space) -> MSE over the training keypoints (mm^2)."""

    base: Material
    free: tuple
    designs: tuple
    measured: np.ndarray
    max_iter: int | None = None

    def __call__(self, x) -> float:
        res = self.residuals(x)
        return float(np.mean(res ** 2))

    def residuals(self, x, executor=None) -> np.ndarray:
        """Predicted minus measured keypoints (mm), flattened, with the penalty of the designs
        whose solve is not certified spread over them (so mean(res^2) is the objective).
        ``executor``: solve the designs in parallel (``predict_keypoints``)."""
        try:
            material = _from_x(x, self.free, self.base)
        except InvalidInputError:
            return np.full(self.measured.size, 1e3)
        pred, bad = predict_keypoints(material, self.designs, self.max_iter, executor)
        res = (pred - self.measured).ravel()
        if bad:
            res = np.sqrt(res ** 2 + UNCONVERGED_PENALTY * bad)
        return res


@dataclass(frozen=True)
class CalibrationResult:
    material: Material
    mse_mm2: float
    free: tuple
    fixed: dict
    generations: int
    evaluations: int
    elapsed_s: float
    message: str
    identifiability: dict = field(default_factory=dict)
    interrupted: bool = False
    #: The search population's spread after each generation: the standard deviation of its
    #: objective values over their mean, the measure scipy's termination compares with ``tol``.
    spreads: tuple = ()


def identifiability(objective: Objective, x: np.ndarray, step: float = 1e-3, executor=None) -> dict:
    """Singular values of d(keypoints)/d(log-parameters) at ``x`` and the weak directions
    (``executor``: solve the designs in parallel)."""
    base, _ = predict_keypoints(_from_x(x, objective.free, objective.base), objective.designs,
                                executor=executor)
    cols = []
    for k in range(x.size):
        xp = x.copy()
        xp[k] += step
        pred, _ = predict_keypoints(_from_x(xp, objective.free, objective.base), objective.designs,
                                    executor=executor)
        cols.append(((pred - base) / step).ravel())
    J = np.array(cols).T
    _, s, vt = np.linalg.svd(J, full_matrices=False)
    weak = []
    for sv, v in zip(s, vt):
        if sv < WEAK_RATIO * s[0]:
            comps = sorted(zip(objective.free, v), key=lambda t: -abs(t[1]))
            weak.append({"singular_value": float(sv),
                         "direction": {n: round(float(c), 3) for n, c in comps if abs(c) > 0.1}})
    return {
        "not_identifiable": f"the overall scale of the energy: {SCALE_PARAM} is held fixed "
                            "and the other coefficients are fitted relative to it",
        "parameters": list(objective.free),
        "singular_values": [float(v) for v in s],
        "condition_number": float(s[0] / s[-1]) if s[-1] > 0 else math.inf,
        "weak_directions": weak,
    }


def search_material(material: Material, nodes: int | None = SEARCH_NODES) -> Material:
    """``material`` on ``nodes`` nodes with the same domain: the largest spacing grows by
    (N - 1) / (nodes - 1), so every design's outer radius stays put (the bending weights are
    defined at a fixed reference spacing, so the physics does not change). ``None`` or at
    least the material's own N: the material itself."""
    if nodes is None or nodes >= material.n_nodes:
        return material
    return material.replace(n_nodes=nodes,
                            dr_max_mm=material.dr_max_mm * (material.n_nodes - 1) / (nodes - 1))


def start_point(x, bounds) -> np.ndarray:
    """``x`` (search coordinates) moved into ``bounds``."""
    return np.clip(np.asarray(x, dtype=float), [b[0] for b in bounds], [b[1] for b in bounds])


def population_spread(energies) -> float:
    """The standard deviation of a population's objective values over their mean: scipy's
    differential evolution stops when it is at most ``tol``."""
    energies = np.asarray(energies, dtype=float)
    return float(np.std(energies) / abs(np.mean(energies)))


def evolve(objective, bounds, x0, *, maxiter: int, popsize: int, seed: int, tol: float,
           executor=None, callback=None):
    """scipy's differential evolution as every fit here runs it: from ``x0`` and a Latin
    hypercube, the population updated once per generation (so one worker and many give the
    same result), without scipy's own polish (``polish_fit`` follows)."""
    from scipy.optimize import differential_evolution

    return differential_evolution(objective, bounds, maxiter=maxiter, popsize=popsize, seed=seed,
                                  tol=tol, x0=x0, workers=executor if executor is not None else 1,
                                  updating="deferred", polish=False, init="latinhypercube",
                                  callback=callback)


def polish_fit(objective: Objective, x, f: float, bounds, max_evaluations: int = POLISH_EVALUATIONS,
               executor=None):
    """(x, objective, evaluations used) after a bounded least-squares polish from ``x``; the
    start is returned unchanged unless the polish lowers the objective below ``f``.
    ``executor``: solve each evaluation's designs in parallel (an ``Objective`` only; the
    result is the same)."""
    from scipy.optimize import least_squares

    lo, hi = np.array([b[0] for b in bounds]), np.array([b[1] for b in bounds])
    x = start_point(x, bounds)
    counter = {"n": 0}

    def fun(v):
        counter["n"] += 1
        return objective.residuals(v, executor) if executor is not None else objective.residuals(v)

    fit = least_squares(fun, x, bounds=(lo, hi), method="trf", diff_step=1e-3, x_scale="jac",
                        max_nfev=max(1, max_evaluations // (x.size + 1)))
    polished = float(np.mean(fit.fun ** 2))
    if polished < f:
        return np.array(fit.x), polished, counter["n"]
    return x, f, counter["n"]


def calibrate(designs, measured, start: Material, *, maxiter: int = 30, popsize: int = 10,
              seed: int = 0, executor=None, free=None, tol: float = DE_TOL, x0=None,
              callback=None, check_identifiability: bool = True, polish: bool = True,
              search_nodes: int | None = SEARCH_NODES) -> CalibrationResult:
    """Differential evolution (scipy) over the free parameters; see the module docstring.

    ``designs``: [(diameter_mm, fill)] of the training rows; ``measured``: (n, 5) keypoints.
    ``executor``: a map-like (``stitchswitch.executor``) for parallel evaluation: the members
    of each generation in the search, the designs of each evaluation in the polish and the
    identifiability report (the result does not depend on it).
    ``tol``: the termination tolerance (module docstring, "Termination").
    ``x0``: a starting point in the search space (resume from a checkpoint).
    ``callback(generation, best_material, best_mse)`` after every generation; it may raise
    KeyboardInterrupt, which ends the search with the best point so far (its MSE is the
    search resolution's). ``polish``: finish with the local least-squares step.
    ``search_nodes``: the resolution of the search (module docstring; None: the start's own)."""
    free = tuple(free or DEFAULT_FREE)
    unknown = [n for n in free if n not in BOUNDS]
    if unknown:
        raise InvalidInputError(f"free parameters: {', '.join(unknown)} cannot be fitted "
                                f"(choose from {', '.join(BOUNDS)})")
    measured = np.asarray(measured, dtype=float)
    if measured.shape != (len(designs), 5) or len(designs) == 0:
        raise InvalidInputError(f"measured: expected ({len(designs)}, 5) keypoints, got {measured.shape}")
    rows = tuple((float(d), float(p)) for d, p in designs)
    objective = Objective(start, free, rows, measured)
    search = Objective(search_material(start, search_nodes), free, rows, measured,
                       SEARCH_MAX_ITER)
    bounds = _search_bounds(free)
    x_start = start_point(_to_x(start.as_dict(), free) if x0 is None else x0, bounds)
    state = {"gen": 0, "best_x": x_start, "best_f": math.inf, "nfev": 0, "spreads": []}
    t0 = time.perf_counter()

    def on_generation(intermediate_result):
        state["gen"] += 1
        state["best_x"], state["best_f"] = np.array(intermediate_result.x), float(intermediate_result.fun)
        state["spreads"].append(population_spread(intermediate_result.population_energies))
        if callback:
            callback(state["gen"], _from_x(state["best_x"], free, start), state["best_f"])

    interrupted = False
    try:
        res = evolve(search, bounds, x_start, maxiter=maxiter, popsize=popsize, seed=seed, tol=tol,
                     executor=executor, callback=on_generation)
        best_x, best_f, message, nfev = res.x, float(res.fun), str(res.message), int(res.nfev)
        coarse = search.base != start
        if polish and coarse:                      # to the search resolution's minimum first
            best_x, _, used = polish_fit(search, best_x, best_f, bounds, executor=executor)
            nfev += used
        if coarse:                                 # the MSE at the start's own resolution
            best_f = float(np.mean(objective.residuals(best_x, executor) ** 2))
            nfev += 1
        if polish:
            best_x, best_f, used = polish_fit(objective, best_x, best_f, bounds, executor=executor)
            nfev += used
            message += f"; polished ({used} evaluations)"
    except KeyboardInterrupt:
        interrupted = True
        best_x, best_f, message, nfev = state["best_x"], state["best_f"], "interrupted", -1
    elapsed_s = time.perf_counter() - t0
    material = _from_x(best_x, free, start)
    ident = (identifiability(objective, np.asarray(best_x), executor=executor)
             if check_identifiability and not interrupted else {})
    fixed = {n: getattr(start, n) for n in PARAMS if n not in free}
    return CalibrationResult(material, best_f, free, fixed, state["gen"], nfev, elapsed_s, message,
                             ident, interrupted, tuple(state["spreads"]))
