"""One design with the shell of revolution: build its problem, find its pop-up equilibrium,
and read its keypoints.

``build`` maps a ``Patch`` and the reduced model's ``Material`` (``moduli``) plus the shell's
own ``ShellParams`` to a ``ShellProblem`` on the reduced model's domain L = (N - 1) dR (the same
far edge, so that the keypoints compare; ``edge`` as in ``problem``).

Starts. ``reduced_start`` is the reduced model's equilibrium, an initial guess only: Newton
(``relax``) leaves it for the shell's own equilibrium. ``cap_start`` is independent of the
reduced model: the embroidered disc as a spherical cap at its natural length, the bare knit
leaving it tangentially and flattening out. ``problem.flat_state()`` is the flat sheet.
``equilibrium`` runs Newton from the reduced start for at most ``GUESS_ITERATIONS``; when that
does not certify, from the flat sheet (kept if it certifies), where ``relax`` follows a negative-curvature mode if
the flat state is a saddle (docs/fem-reference.md, "Starts"). The result is certified when
converged with lowest scaled eigenvalue > ``MIN_EIGENVALUE`` (a strict local minimum), or,
when that eigenvalue is within the eigensolver's round-off (|mu| <= ``MIN_EIGENVALUE``) and the
second is above it, when the energy's curvature along the lowest mode is positive and
resolved at an amplitude of ``MODE_AMPLITUDE`` R_b (``newton.resolved_curvature``): with the
spectral gap, the mode's curvature is then the lowest eigenvalue's sign to second order.
Flat states of the relaxed knit sit in that band (docs/fem-reference.md, "Starts").
"""
from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from stitchswitch.fem_reference.revolution.meridian import Meridian
from stitchswitch.fem_reference.revolution.moduli import force_scale_n_per_model, region_moduli
from stitchswitch.fem_reference.revolution.newton import (
    MIN_EIGENVALUE,
    lowest_modes,
    minimize,
    resolved_curvature,
)
from stitchswitch.fem_reference.revolution.params import DEFAULT_SHELL, ShellParams
from stitchswitch.fem_reference.revolution.problem import ShellProblem
from stitchswitch.reduced.model.discretization import make_grid
from stitchswitch.reduced.model.keypoints import Keypoints, keypoints_from_profile
from stitchswitch.reduced.model.params import DEFAULT_MATERIAL, Material, Patch

MAX_RESTARTS = 3
#: Newton iterations allowed from the reduced model's guess before the flat start is tried:
#: of the model-error table's 54 solves, those that certify from the guess take at most 115
#: (d 25 mm, p 0.6 without hoop bending; docs/fem-reference.md, "Starts"); d 25 mm, p 1.0
#: wandered for 379-385 iterations into a folded flat state of higher energy than the one
#: the flat sheet reaches in 20.
GUESS_ITERATIONS = 150
#: Tangent angle (rad) at the embroidery boundary of ``cap_start``'s spherical cap.
CAP_ANGLE = 1.4
#: Spacing of the profile the keypoints are read from, as a fraction of R_b.
SAMPLE_FRACTION = 1.0 / 200.0
#: Amplitude of the energy's second difference along a round-off-level mode, as a fraction of
#: R_b: large enough for the difference to stand far above the energy's round-off, small
#: enough to stay in the quadratic regime (measured: d 25 mm, p 1.0 flat, 6.0e-11 / 6.0e-9 /
#: 6.0e-7 at 1e-3 / 1e-2 / 1e-1 mm).
MODE_AMPLITUDE = 1e-3


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
    iterations, the two lowest eigenvalues of the scaled Hessian, wall time, and
    ``soft_mode_rises``: whether the lowest eigenvalue is within the round-off band, the second
    above it, and the energy's curvature along the lowest mode positive and resolved
    (``newton.resolved_curvature``)."""

    problem: ShellProblem
    y: np.ndarray
    energy: float
    residual: float
    converged: bool
    iterations: int
    lowest_eigenvalue: float
    solve_s: float
    second_eigenvalue: float = np.inf
    soft_mode_rises: bool = False

    @property
    def certified(self) -> bool:
        """Converged and a strict local minimum (the module docstring)."""
        return bool(self.converged and (self.lowest_eigenvalue > MIN_EIGENVALUE or self.soft_mode_rises))

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


def cap_start(problem: ShellProblem, angle: float = CAP_ANGLE, decay: float = 0.5) -> np.ndarray:
    """A start independent of the reduced model: inside, a spherical cap at its natural length
    (meridional strain 0) whose tangent makes ``angle`` (rad) with the plane at R_b; outside,
    the bare knit at its rest length, leaving the cap tangentially with its angle decaying as
    exp(-(S - R_b) / (decay R_b)). Held edges blend r back to S at the frame, as
    ``reduced_start`` does."""
    mer = problem.meridian
    rb, L, lam = mer.rb, mer.length, problem.inner_moduli.lam
    n = 200
    S_in = np.linspace(0.0, rb, n + 1)
    rho = lam * rb / angle
    r_in, z_in = rho * np.sin(lam * S_in / rho), rho * np.cos(lam * S_in / rho)
    S_out = np.linspace(rb, L, 4 * n + 1)
    theta = angle * np.exp(-(S_out - rb) / (decay * rb))
    mid = 0.5 * (theta[1:] + theta[:-1])
    step = np.diff(S_out)
    r_out = r_in[-1] + np.concatenate([[0.0], np.cumsum(np.cos(mid) * step)])
    z_out = z_in[-1] - np.concatenate([[0.0], np.cumsum(np.sin(mid) * step)])
    R = np.concatenate([S_in, S_out[1:]])
    r = np.concatenate([r_in, r_out[1:]])
    z = np.concatenate([z_in, z_out[1:]])
    z = z - z[-1]
    if problem.edge != "free":
        r = r + np.clip((R - rb) / max(L - rb, 1e-9), 0.0, 1.0) * (R - r)
    return from_profile(problem, R, r, z, n)


def relax(problem: ShellProblem, y0: np.ndarray, *, max_iter: int = 300, tol: float | None = None) -> ShellState:
    """Newton from ``y0``; from a saddle, restarts along the negative-curvature mode."""
    kw = {} if tol is None else {"tol": tol}
    total_it, total_s = 0, 0.0
    y = y0
    for _ in range(MAX_RESTARTS + 1):
        res = minimize(problem, y, max_iter=max_iter, **kw)
        total_it += res.iterations
        total_s += res.solve_s
        (mu, mu2), (v, _) = lowest_modes(problem, res.y, 2)
        if not (res.converged and mu < -MIN_EIGENVALUE):
            break
        # a saddle: step along the mode, to the side that raises the apex
        apex = problem.meridian.dof("inner", "z", 0)
        v = v * (np.sign(v[apex]) or 1.0) / max(float(np.max(np.abs(v))), 1e-300)
        y = res.y + 0.05 * problem.meridian.rb * v
    rises = bool(res.converged and abs(mu) <= MIN_EIGENVALUE < mu2
                 and resolved_curvature(problem, res.y, v, MODE_AMPLITUDE * problem.meridian.rb))
    return ShellState(problem, res.y, res.energy, res.residual, res.converged, total_it, float(mu),
                      total_s, float(mu2), rises)


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


def settled(problem: ShellProblem, patch: Patch, material: Material, *,
            max_iter: int = 300, guess_iterations: int = GUESS_ITERATIONS) -> ShellState:
    """Newton from the reduced model's guess (``guess_iterations`` at most); if that does not
    certify, from the flat sheet. The flat run's state if it certifies, else the guess run's
    (uncertified); iterations and time are those of both runs."""
    guess = relax(problem, reduced_start(problem, patch, material),
                  max_iter=min(max_iter, guess_iterations))
    if guess.certified:
        return guess
    flat = relax(problem, problem.flat_state(), max_iter=max_iter)
    kept = flat if flat.certified else guess
    return replace(kept, iterations=guess.iterations + flat.iterations,
                   solve_s=guess.solve_s + flat.solve_s)


def equilibrium(patch: Patch, material: Material = DEFAULT_MATERIAL, params: ShellParams = DEFAULT_SHELL,
                *, edge: str = "free", refine: int = 0, max_iter: int = 300,
                start: np.ndarray | None = None) -> ShellState:
    """The pop-up equilibrium of one design: ``settled``, or Newton from ``start`` if given."""
    problem = build(patch, material, params, edge=edge, refine=refine)
    if start is None:
        return settled(problem, patch, material, max_iter=max_iter)
    return relax(problem, start, max_iter=max_iter)
