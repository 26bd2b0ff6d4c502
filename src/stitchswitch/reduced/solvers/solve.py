"""Public entry point of the reduced model: ``solve(patch, material) -> Solution``."""
from __future__ import annotations

import time
from dataclasses import dataclass, field

import numpy as np

from stitchswitch.errors import InvalidInputError
from stitchswitch.reduced.model.discretization import make_grid
from stitchswitch.reduced.model.params import DEFAULT_MATERIAL, SOLVERS, Material, Patch
from stitchswitch.reduced.solvers import continuation, newton

#: Certificate threshold: the solution is reported converged only if the max-norm of the
#: projected gradient (dimensionless energy per dR) is at most this. It sits above the
#: certificate's round-off floor: at the compressed small patches (d 20-25 mm, p 1.0) moving
#: every coordinate of the solution by up to 2 ulps gives residuals of 8e-11 (median) to 2e-10
#: (docs/model.md), so a smaller threshold is met only by chance.
DEFAULT_TOL = 1e-9
#: A result lower than this everywhere (mm) is flat (``_solve`` tries a taller seed then).
FLAT_MM = 1e-3


@dataclass(frozen=True)
class Solution:
    """An equilibrium profile and its certificate.

    ``R_mm``: rest radius of every node (relaxed-fabric frame). ``r_mm, z_mm``: deformed radius
    and height, z = 0 at the outermost node. ``n_inside``: index of the node on the embroidery
    boundary. ``residual``: max-norm of the projected gradient of the bound-constrained problem
    (dimensionless, dR units). ``converged``: residual <= tol. ``second_order``: the reduced
    Hessian at the solution is positive definite (a strict local minimum); None if not checked.
    ``solve_s``: wall time of the solve in seconds.
    """

    patch: Patch
    material: Material
    solver: str
    R_mm: np.ndarray
    r_mm: np.ndarray
    z_mm: np.ndarray
    n_inside: int
    dr_mm: float
    energy: float
    residual: float
    converged: bool
    iterations: int
    solve_s: float
    message: str
    second_order: bool | None = None
    tol: float = DEFAULT_TOL
    _cache: dict = field(default_factory=dict, repr=False, compare=False)

    @property
    def certified(self) -> bool:
        """Converged and a strict local minimum: the result this package stands behind."""
        return bool(self.converged and self.second_order)

    @property
    def keypoints(self):
        """The five measurable quantities (``stitchswitch.reduced.model.keypoints``)."""
        if "kp" not in self._cache:
            from stitchswitch.reduced.model.keypoints import keypoints
            self._cache["kp"] = keypoints(self)
        return self._cache["kp"]

    def as_dict(self) -> dict:
        """Scalars only (no profile): what ``stitchswitch simulate --json`` prints."""
        kp = self.keypoints
        return {
            "d_mm": self.patch.diameter_mm, "fill": self.patch.fill, "solver": self.solver,
            "h_mm": kp.h_mm, "r_a_mm": kp.r_a_mm, "z_a_mm": kp.z_a_mm,
            "r_b_mm": kp.r_b_mm, "z_b_mm": kp.z_b_mm, "r_b_rule": kp.b_rule,
            "energy": self.energy, "residual": self.residual, "converged": self.converged,
            "second_order": self.second_order, "iterations": self.iterations,
            "solve_s": self.solve_s, "message": self.message,
            "n_nodes": int(self.r_mm.size), "n_inside": self.n_inside, "dr_mm": self.dr_mm,
        }


def _ro(a) -> np.ndarray:
    a = np.array(a, dtype=float)
    a.setflags(write=False)
    return a


def _warm_profile(warm: Solution, grid) -> tuple[np.ndarray, np.ndarray]:
    """Resample a neighbouring design's profile onto this grid, in boundary-normalized
    coordinates (R / R_boundary), scaled to this design's size."""
    s_old = warm.R_mm / warm.R_mm[warm.n_inside]
    s_new = grid.R / grid.n_inside
    scale = grid.n_inside / (warm.R_mm[warm.n_inside] / warm.dr_mm)
    r = np.interp(s_new, s_old, warm.r_mm / warm.dr_mm * scale, right=np.nan)
    z = np.interp(s_new, s_old, warm.z_mm / warm.dr_mm * scale, right=0.0)
    tail = np.isnan(r)
    r[tail] = grid.R[tail] + (r[~tail][-1] - grid.R[~tail][-1])
    from stitchswitch.reduced.solvers.constraints import project
    return project(r, z)


def solve(patch: Patch, material: Material = DEFAULT_MATERIAL, *, solver: str = "newton",
          tol: float = DEFAULT_TOL, max_iter: int | None = None,
          warm_start: Solution | None = None, terms=None, **solver_options) -> Solution:
    """Equilibrium profile of one design (with one BLAS thread: ``stitchswitch.blas``).

    ``solver="newton"`` (default): the certified projected Newton method, started from the
    released state (``continuation.released_state``: the flat hoop state with a small upward
    seed bump, the same start as the Adam baseline), or from ``warm_start`` (a neighbouring
    design's Solution) if given, with at most half the iteration budget, then from the
    released state. If that does not converge, the release continuation of the rest metric is
    tried with the remaining budget. A result that ends flat is solved once more from a
    taller seed bump (``continuation.RETRY_SEED_FRACTION``), and the lower certified state is
    kept: a flat equilibrium can be a strict local minimum above a popped one. ``solver="adam"``: the paper's projected
    Adam with gradient clipping from the same released state; its result is certified the
    same way and is usually *not* converged. ``terms`` replaces the energy terms (Newton only;
    default ``terms.ALL_TERMS``): discretization variants and added effects. ``max_iter``
    bounds Newton
    iterations (default 500) or Adam steps (default 20000)."""
    from stitchswitch.blas import one_thread

    with one_thread():
        return _solve(patch, material, solver=solver, tol=tol, max_iter=max_iter,
                      warm_start=warm_start, terms=terms, **solver_options)


def _solve(patch: Patch, material: Material, *, solver: str, tol: float, max_iter: int | None,
           warm_start: Solution | None, terms, **solver_options) -> Solution:
    if solver not in SOLVERS:
        raise InvalidInputError(f"solver: {solver!r} is not one of {', '.join(SOLVERS)}")
    if not (np.isfinite(tol) and tol > 0):
        raise InvalidInputError(f"tol: {tol!r} must be a positive number")
    if terms is not None and solver != "newton":
        raise InvalidInputError(f"terms: custom energy terms need solver='newton', not {solver!r}")
    grid = make_grid(patch, material)
    t0 = time.perf_counter()
    if solver == "newton":
        budget = 500 if max_iter is None else int(max_iter)
        result, used = None, 0
        prepared = newton.prepare(grid, terms)        # one set of coefficients for each start
        if warm_start is not None:
            r0, z0 = _warm_profile(warm_start, grid)
            # at most half the budget: a warm start that fails leaves the cold start room
            result = newton.minimize(grid, r0, z0, tol=tol, max_iter=budget // 2,
                                     prepared=prepared)
            used = result.iterations
            if not result.converged:
                result = None
        if result is None:
            result = newton.minimize(grid, *continuation.released_state(grid), tol=tol,
                                     max_iter=max(budget - used, 0), prepared=prepared)
            used += result.iterations
        if not result.converged and used < budget:
            result, more = continuation.release(grid, tol=tol, max_iter=budget - used,
                                                terms=terms)
            used += more
        if result.converged and np.max(result.z) * grid.dr_mm < FLAT_MM and used < budget:
            # flat is an equilibrium of every design and may be a local minimum above a popped
            # one: try a taller seed and keep the lower certified state
            retry = newton.minimize(grid, *continuation.released_state(
                grid, continuation.RETRY_SEED_FRACTION), tol=tol, max_iter=budget - used,
                prepared=prepared)
            used += retry.iterations
            if retry.converged and retry.second_order and retry.energy < result.energy:
                result = retry
    else:
        from stitchswitch.reduced.solvers import adam
        steps = 20000 if max_iter is None else int(max_iter)
        result = adam.minimize(grid, *continuation.released_state(grid),
                               tol=tol, steps=steps, **solver_options)
        used = result.iterations
    solve_s = time.perf_counter() - t0
    return Solution(
        patch=patch, material=material, solver=solver,
        R_mm=_ro(grid.R * grid.dr_mm), r_mm=_ro(result.r * grid.dr_mm),
        z_mm=_ro(result.z * grid.dr_mm), n_inside=grid.n_inside, dr_mm=grid.dr_mm,
        energy=float(result.energy), residual=float(result.residual),
        converged=bool(result.converged), iterations=int(used), solve_s=solve_s,
        message=result.message, second_order=result.second_order, tol=tol,
    )
