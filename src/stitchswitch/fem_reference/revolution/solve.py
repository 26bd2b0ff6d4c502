"""One design with the shell of revolution: build its problem, find its pop-up equilibrium
independently of the reduced model, and read its keypoints.

``build`` maps a ``Patch`` and the reduced model's ``Material`` (``moduli``) plus the shell's
own ``ShellParams`` to a ``ShellProblem`` on the reduced model's domain L = (N - 1) dR (the same
far edge, so that the keypoints compare; ``edge`` as in ``problem``).

``equilibrium`` starts from the flat sheet raised by a smooth bump (a quartic cap of height
``SEED_FRACTION`` R_b inside the patch; the flat sheet itself is a stationary point by the
z -> -z symmetry) and runs Newton (``newton.minimize``) at full prestretch. If Newton ends on a
saddle (lowest eigenvalue < 0) it restarts along the negative-curvature mode, on the side of
higher apex, up to ``MAX_RESTARTS`` times. The result is certified: converged and its lowest
eigenvalue > ``MIN_EIGENVALUE`` (a strict local minimum). Nothing of the reduced model but its
material constants and its domain length is used.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from stitchswitch.fem_reference.revolution.meridian import Meridian
from stitchswitch.fem_reference.revolution.moduli import force_scale_n_per_model, region_moduli
from stitchswitch.fem_reference.revolution.newton import MIN_EIGENVALUE, lowest_mode, minimize
from stitchswitch.fem_reference.revolution.params import DEFAULT_SHELL, ShellParams
from stitchswitch.fem_reference.revolution.problem import ShellProblem
from stitchswitch.reduced.model.discretization import make_grid
from stitchswitch.reduced.model.keypoints import Keypoints, keypoints_from_profile
from stitchswitch.reduced.model.params import DEFAULT_MATERIAL, Material, Patch

SEED_FRACTION = 0.3
MAX_RESTARTS = 3
#: Spacing of the profile the keypoints are read from, as a fraction of R_b.
SAMPLE_FRACTION = 1.0 / 200.0


def build(patch: Patch, material: Material = DEFAULT_MATERIAL, params: ShellParams = DEFAULT_SHELL,
          *, edge: str = "free", refine: int = 0, length_mm: float | None = None) -> ShellProblem:
    """The problem of one design on [0, L]: L = ``length_mm`` or the reduced model's domain."""
    grid = make_grid(patch, material)
    rb = patch.diameter_mm / (2.0 * material.eta)
    length = (material.n_nodes - 1) * grid.dr_mm if length_mm is None else float(length_mm)
    mer = Meridian(rb, length, params.elements_inside, params.growth, params.intorder, refine)
    inner, outer = region_moduli(patch, material, params)
    weight = 0.0
    if params.areal_weight_n_per_m2:
        # self weight in model units: q A_fab / Y per mm of height (moduli.force_scale_n_per_model)
        weight = params.areal_weight_n_per_m2 * 2.0 * np.pi * 1e-6 / force_scale_n_per_model(material, params)
    return ShellProblem(mer, inner, outer, edge=edge, weight=weight)


@dataclass(frozen=True)
class ShellState:
    """An equilibrium of ``problem``: unknowns ``y``, energy (model units, mm^2), residual,
    iterations, lowest eigenvalue of the scaled Hessian and wall time."""

    problem: ShellProblem
    y: np.ndarray
    energy: float
    residual: float
    converged: bool
    iterations: int
    lowest_eigenvalue: float
    solve_s: float

    @property
    def certified(self) -> bool:
        """Converged and a strict local minimum."""
        return bool(self.converged and self.lowest_eigenvalue > MIN_EIGENVALUE)

    @property
    def apex_mm(self) -> float:
        return float(self.problem.meridian.node_values(self.y)[2][0])

    def profile(self):
        """(S, r, z, n_inside) sampled every R_b / 200, a point on R_b."""
        mer = self.problem.meridian
        return mer.sample(self.y, mer.rb * SAMPLE_FRACTION)

    @property
    def keypoints(self) -> Keypoints:
        S, r, z, n = self.profile()
        return keypoints_from_profile(S, r, z - z[-1], n)


def seed(problem: ShellProblem, fraction: float = SEED_FRACTION, sign: float = 1.0) -> np.ndarray:
    """The flat sheet with the quartic cap sign * fraction R_b (1 - (S/R_b)^2)^2 inside."""
    mer = problem.meridian
    y = problem.flat_state()
    rb = mer.rb
    for k, S in enumerate(mer.inner_nodes):
        u = S / rb
        y[mer.dof("inner", "z", k)] += sign * fraction * rb * (1 - u * u) ** 2
        if k:
            y[mer.dof("inner", "dz", k)] += sign * fraction * rb * 2 * (1 - u * u) * (-2 * u) / rb
    return y


def relax(problem: ShellProblem, y0: np.ndarray, *, max_iter: int = 300, tol: float | None = None) -> ShellState:
    """Newton from ``y0``; from a saddle, restarts along the negative-curvature mode."""
    kw = {} if tol is None else {"tol": tol}
    total_it, total_s = 0, 0.0
    y = y0
    for _ in range(MAX_RESTARTS + 1):
        res = minimize(problem, y, max_iter=max_iter, **kw)
        total_it += res.iterations
        total_s += res.solve_s
        mu, v = lowest_mode(problem, res.y)
        if not (res.converged and mu < -MIN_EIGENVALUE):
            break
        # a saddle: step along the mode, to the side that raises the apex
        apex = problem.meridian.dof("inner", "z", 0)
        v = v * (np.sign(v[apex]) or 1.0) / max(float(np.max(np.abs(v))), 1e-300)
        y = res.y + 0.05 * problem.meridian.rb * v
    return ShellState(problem, res.y, res.energy, res.residual, res.converged, total_it, mu, total_s)


def from_profile(problem: ShellProblem, R_mm, r_mm, z_mm, n_inside: int) -> np.ndarray:
    """Unknowns interpolating a profile given at rest radii ``R_mm`` with point ``n_inside`` on
    R_b: a cubic spline per side, so the stretch may jump at the boundary."""
    from scipy.interpolate import CubicSpline

    mer = problem.meridian
    xs = []
    for side, nodes, part in ((mer.inner, mer.inner_nodes, slice(0, n_inside + 1)),
                              (mer.outer, mer.outer_nodes, slice(n_inside, None))):
        x = np.zeros(2 * side.n)
        R = np.asarray(R_mm)[part]
        for k, prof in enumerate((r_mm, z_mm)):
            spline = CubicSpline(R, np.asarray(prof)[part])
            at = np.clip(nodes, R[0], R[-1])
            x[k * side.n + side.value] = spline(at)
            x[k * side.n + side.slope] = spline(at, 1)
        xs.append(x)
    y = mer.from_sides(*xs)
    flat = problem.flat_state()
    y[problem.fixed] = flat[problem.fixed]
    y[mer.dof("inner", "dz", 0)] = 0.0
    y[mer.dof("outer", "z", mer.outer_nodes.size - 1)] = 0.0
    return y


def reduced_start(problem: ShellProblem, patch: Patch, material: Material) -> np.ndarray:
    """The reduced model's equilibrium as a starting guess (only a guess: Newton then finds the
    shell's own equilibrium), mirrored to the pop-up side."""
    from stitchswitch.reduced.solvers.solve import solve

    red = solve(patch, material)
    R, r = np.asarray(red.R_mm), np.asarray(red.r_mm)
    z = np.asarray(red.z_mm) - np.interp(problem.meridian.length, R, red.z_mm)
    if problem.edge != "free":      # held at r(L) = L: blend the far fabric back to rest
        L = problem.meridian.length
        blend = np.clip((R - problem.meridian.rb) / max(L - problem.meridian.rb, 1e-9), 0.0, 1.0)
        r = r + blend * (R - r)
    return from_profile(problem, R, r, z, red.n_inside)


def equilibrium(patch: Patch, material: Material = DEFAULT_MATERIAL, params: ShellParams = DEFAULT_SHELL,
                *, edge: str = "free", refine: int = 0, max_iter: int = 300,
                start: np.ndarray | None = None) -> ShellState:
    """The pop-up equilibrium of one design from ``start`` (default: ``reduced_start``)."""
    problem = build(patch, material, params, edge=edge, refine=refine)
    y0 = reduced_start(problem, patch, material) if start is None else start
    return relax(problem, y0, max_iter=max_iter)
