"""The contact plate of the switching experiment and its unilateral contact with the shell.

Radius rule (docs/fem-reference.md, "Switching"): the paper's Appendix B used "a contact plate
sized according to the patch diameter", with contact areas 0.44-15.9 cm^2 over d = 20-90 mm and
no rule given. We take the power law through those two extremes, the smallest area at the
smallest patch and the largest at the largest:

    area(d) = 0.44 cm^2 (d / 20 mm)^k,  k = ln(15.9 / 0.44) / ln(90 / 20) = 2.385,

radius sqrt(area / pi): 3.7 mm at d = 20 mm, 22.5 mm at d = 90 mm (0.37 and 0.50 of the patch
radius).

Contact: the plate is rigid, flat, frictionless, at height w, pushing down. The shell's mesh
nodes whose radius r is at most the plate radius (``eligible_nodes``) may not rise above it.
The unilateral constraint is solved by an active set (``contact_solve``): the nodes in contact
are held at z = w (their z unknowns pinned) and Newton solves for the rest; the nodes whose
reaction would pull the plate down (-dE/dz_i < 0) leave the set, the eligible nodes above the
plate join it, until the set no longer changes. The contact force on the plate is the sum of
the reactions, F = -sum_i dE/dz_i over the set (model units; ``moduli.force_scale_n_per_model``
converts to N): no penalty, no penetration.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

AREA_SMALL_CM2, AREA_LARGE_CM2 = 0.44, 15.9
D_SMALL_MM, D_LARGE_MM = 20.0, 90.0
EXPONENT = math.log(AREA_LARGE_CM2 / AREA_SMALL_CM2) / math.log(D_LARGE_MM / D_SMALL_MM)


def plate_radius_mm(diameter_mm: float) -> float:
    """The contact plate's radius for a patch of diameter ``diameter_mm`` (module docstring)."""
    area_mm2 = 100.0 * AREA_SMALL_CM2 * (diameter_mm / D_SMALL_MM) ** EXPONENT
    return math.sqrt(area_mm2 / math.pi)


@dataclass(frozen=True)
class Contact:
    """A converged contact solve: the state, the z dofs in contact, the force on the plate."""

    y: np.ndarray
    nodes: tuple
    force: float
    converged: bool
    iterations: int


def contact_solve(problem, y, w_mm: float, radius_mm: float, *, max_iter: int = 200,
                  max_rounds: int = 12) -> Contact:
    """The shell pressed by the plate at height ``w_mm`` from the state ``y`` (module
    docstring)."""
    from stitchswitch.fem_reference.revolution.newton import minimize

    eligible = eligible_nodes(problem, y, radius_mm)
    active = [int(i) for i in eligible if y[i] >= w_mm]
    iterations = 0
    for _ in range(max_rounds):
        y0 = y.copy()
        y0[active] = w_mm
        if not np.isfinite(problem.energy(y0)):
            y0 = y.copy()
        y0[active] = w_mm
        res = minimize(problem.with_(pinned=active), y0, max_iter=max_iter)
        iterations += res.iterations
        _, g, _ = problem.evaluate(res.y, 1)
        reaction = {i: -float(g[i]) for i in active}
        eligible = eligible_nodes(problem, res.y, radius_mm)
        above = [int(i) for i in eligible if res.y[i] > w_mm + 1e-9 and i not in reaction]
        pulling = [i for i, f in reaction.items() if f < 0.0]
        if not above and not pulling:
            break
        keep = set(active) - set(pulling)
        active = sorted(keep | (set(above) & set(int(i) for i in eligible)))
        y = res.y
    force = float(sum(reaction.values()))
    return Contact(res.y, tuple(active), force, bool(res.converged), iterations)


def eligible_nodes(problem, y: np.ndarray, radius_mm: float) -> np.ndarray:
    """The z dofs of the mesh nodes with r <= ``radius_mm`` (the interface node once)."""
    mer = problem.meridian
    _, r, _ = mer.node_values(y)
    n_in = mer.inner_nodes.size
    dofs = [mer.dof("inner", "z", k) for k in range(n_in)]
    dofs += [mer.dof("outer", "z", k) for k in range(1, mer.outer_nodes.size)]
    dofs = np.array(dofs)
    fixed = set(problem.fixed.tolist())
    keep = np.array([r[i] <= radius_mm and dofs[i] not in fixed for i in range(dofs.size)])
    return dofs[keep]
