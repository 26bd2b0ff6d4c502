"""The two stable states of a patch held in the switching experiment, and whether it is
bistable or springs back.

The outer fabric is held as in the experiment (docs/fem-reference.md, "Switching"): clamped flat
in a frame at rest radius ``HOLD_FACTOR`` R_b (r = S, z = 0 there, the slope free), a frame a
little larger than the patch. ``popped_up`` is the shell's pop-up equilibrium in that frame;
``inverted`` starts Newton from its mirror image z -> -z and relaxes without load. The patch is
**bistable** when that relaxed state is a strict local minimum (certified) with its apex below
the rim (z(0) < z(R_b)); otherwise it **springs back** (Newton returns to the pop-up side, or to
no certified state). With kappa_0 = 0 and no gravity the energy is symmetric in z, so every
popped design is bistable; a natural curvature kappa_0 of the embroidered layer breaks the
symmetry.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from stitchswitch.fem_reference.revolution.params import DEFAULT_SHELL, ShellParams
from stitchswitch.fem_reference.revolution.problem import ShellProblem
from stitchswitch.fem_reference.revolution.solve import ShellState, build, relax, settled
from stitchswitch.reduced.model.params import DEFAULT_MATERIAL, Material, Patch

HOLD_FACTOR = 5.0
#: Apex heights (mm) below which a state counts as flat, not popped.
FLAT_MM = 0.05
#: Newton iterations for the mirror image: springing back is the long way from below the rim
#: to the pop-up state (354 iterations measured at d 44 mm, p 0.78, kappa_0 0.05 /mm, 410 at
#: 0.1 /mm; with the solves' default 300 both ended uncertified).
MIRROR_ITERATIONS = 1000


def held_problem(patch: Patch, material: Material = DEFAULT_MATERIAL,
                 params: ShellParams = DEFAULT_SHELL, hold_factor: float = HOLD_FACTOR) -> ShellProblem:
    rb = patch.diameter_mm / (2.0 * material.eta)
    return build(patch, material, params, edge="held", length_mm=hold_factor * rb)


def mirrored(problem: ShellProblem, y: np.ndarray) -> np.ndarray:
    """z -> -z (values and slopes of both sides)."""
    mer = problem.meridian
    out = y.copy()
    for side in ("inner", "outer"):
        nodes = mer.inner_nodes if side == "inner" else mer.outer_nodes
        for k in range(nodes.size):
            out[mer.dof(side, "z", k)] = -y[mer.dof(side, "z", k)]
            if side == "inner" or k:
                out[mer.dof(side, "dz", k)] = -y[mer.dof(side, "dz", k)]
    return out


def rim_mm(problem: ShellProblem, y: np.ndarray) -> float:
    """z at the embroidery boundary."""
    return float(y[problem.meridian.dof("inner", "z", problem.meridian.inner_nodes.size - 1)])


def is_inverted(problem: ShellProblem, state: ShellState) -> bool:
    """A certified state with its apex below the rim by more than ``FLAT_MM``."""
    return bool(state.certified and state.apex_mm < rim_mm(problem, state.y) - FLAT_MM)


def popped_up(problem: ShellProblem, patch: Patch, material: Material) -> ShellState:
    """The pop-up state in the frame: Newton from the reduced model's equilibrium, its far
    fabric blended back to rest at the frame (``solve.reduced_start``), for up to 300
    iterations (a pop-up with natural curvature took 122); if that does not certify, from the
    flat sheet (``solve.settled``)."""
    return settled(problem, patch, material, guess_iterations=300)


@dataclass(frozen=True)
class Bistability:
    """Both states of one design in the frame, and the verdict."""

    patch: Patch
    popup: ShellState
    inverted: ShellState        # the relaxed mirror image (maybe back on the pop-up side)
    popped: bool                # the pop-up state is certified and not flat
    bistable: bool

    @property
    def verdict(self) -> str:
        if not self.popped:
            return "flat"
        return "bistable" if self.bistable else "spring-back"

    def as_dict(self) -> dict:
        return {"d_mm": self.patch.diameter_mm, "fill": self.patch.fill, "verdict": self.verdict,
                "popup_apex_mm": self.popup.apex_mm, "popup_energy": self.popup.energy,
                "popup_certified": self.popup.certified,
                "inverted_apex_mm": self.inverted.apex_mm, "inverted_energy": self.inverted.energy,
                "inverted_certified": self.inverted.certified}


def bistability(patch: Patch, material: Material = DEFAULT_MATERIAL,
                params: ShellParams = DEFAULT_SHELL, hold_factor: float = HOLD_FACTOR) -> Bistability:
    problem = held_problem(patch, material, params, hold_factor)
    up = popped_up(problem, patch, material)
    popped = bool(up.certified and up.apex_mm - rim_mm(problem, up.y) > FLAT_MM)
    down = relax(problem, mirrored(problem, up.y), max_iter=MIRROR_ITERATIONS)
    return Bistability(patch, up, down, popped, bool(popped and is_inverted(problem, down)))
