"""Snap-through by the contact plate, as in the paper's Appendix B: the force-displacement
curve, the switching force, the energy barrier, and the state the patch switches to.

The patch is held in its frame (``states``) in its pop-up state; the plate (``plate``) touches
the apex and is lowered in ``steps`` equal steps of its height w (displacement control, so the
path passes the force maximum that a weight-loaded test jumps from). At every step the shell is
re-solved with the plate's unilateral contact (``plate.contact_solve``: an active set of nodes
held at the plate, updated until it no longer changes) from the previous step's state (no
predictor: the nodes in contact are moved to the plate, every other unknown only by Newton),
and the contact force F(w) >= 0 (the reactions) and the elastic energy are recorded. The path
ends when the plate loses contact (F = 0 after a positive force: the patch has snapped away
from it, or sits on the ridge between its two basins, where one more step on the apex alone
starts the snap on the pushed side) or the plate reaches -``DEPTH`` h. The last state is then
relaxed without load, and the result says whether it is the inverted state (certified strict
minimum, apex below the rim: ``states.is_inverted``).

* Switching force: the largest F on the path, the limit point of the force-controlled
  experiment (slotted weights added until the patch switches). It is refined: the two steps
  around the largest sampled force are re-run with ``REFINE`` sub-steps from the converged state
  before them, and a parabola through the three largest refined samples gives the maximum.
* Energy barrier: the largest elastic energy on the path minus the pop-up energy, i.e. the work
  done by the plate up to the point where the patch would hold itself (F back to 0; ``_barrier``
  extrapolates the force linearly to that point from the last two samples in contact). It is the
  barrier along this axisymmetric path, an upper bound of the true one (a non-axisymmetric path
  may cost less).
* Units: model units (mm^2 energy, mm force); ``force_scale_n_per_model`` gives newtons and
  N mm.
"""
from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np

from stitchswitch.errors import StitchSwitchError
from stitchswitch.fem_reference.revolution.moduli import force_scale_n_per_model
from stitchswitch.fem_reference.revolution.newton import minimize
from stitchswitch.fem_reference.revolution.params import DEFAULT_SHELL, ShellParams
from stitchswitch.fem_reference.revolution.solve import ShellState, relax
from stitchswitch.fem_reference.snap.plate import contact_solve, plate_radius_mm
from stitchswitch.fem_reference.snap.states import HOLD_FACTOR, held_problem, is_inverted, popped_up, rim_mm
from stitchswitch.reduced.model.params import DEFAULT_MATERIAL, Material, Patch

REFINE = 8
#: The apex step (fraction of h) that starts the snap once the plate has lost contact.
SNAP_NUDGE = 0.02
#: The plate travels from the apex height h down to -DEPTH h at most.
DEPTH = 1.5
#: A plate step whose solve fails is retried halved, at most this many times.
MAX_HALVINGS = 3
STEP_MAX_ITER = 200
#: Forces below this (model units) count as no contact.
NO_FORCE = 1e-10


@dataclass(frozen=True)
class SwitchingPath:
    patch: Patch
    plate_radius_mm: float
    w_mm: np.ndarray             # plate height per step
    force: np.ndarray            # contact force (model units)
    elastic_energy: np.ndarray   # shell energy without the plate (model units)
    apex_mm: np.ndarray
    converged: np.ndarray
    switching_force: float       # model units, refined maximum of the force
    w_switch_mm: float           # plate height at the maximum
    barrier: float               # largest elastic energy on the path - pop-up energy
    popup: ShellState
    final: ShellState            # the last state relaxed without load
    inverted: bool
    newton_per_n: float          # newtons per model force unit
    elapsed_s: float

    @property
    def limit_point(self) -> bool:
        """The largest force is a maximum inside the path (the force falls after it), not the
        force at the end of the plate's travel."""
        k = int(np.argmax(self.force))
        return bool(0 < k < self.force.size - 1 and self.force[-1] < self.force[k])

    @property
    def switching_force_n(self) -> float:
        return self.switching_force * self.newton_per_n

    @property
    def barrier_mj(self) -> float:
        """The barrier in mJ: model energy (mm^2) x N/model x mm = N mm = mJ."""
        return self.barrier * self.newton_per_n

    def as_dict(self) -> dict:
        kp_up, kp_down = self.popup.keypoints, self.final.keypoints
        return {
            "d_mm": self.patch.diameter_mm, "fill": self.patch.fill,
            "plate_radius_mm": self.plate_radius_mm,
            "switching_force_n": self.switching_force_n, "w_switch_mm": self.w_switch_mm,
            "energy_barrier_mj": self.barrier_mj, "inverted": self.inverted,
            "limit_point": self.limit_point,
            "all_converged": bool(self.converged.all()),
            "popup": {"h_mm": kp_up.h_mm, "r_a_mm": kp_up.r_a_mm, "z_a_mm": kp_up.z_a_mm,
                      "r_b_mm": kp_up.r_b_mm, "z_b_mm": kp_up.z_b_mm,
                      "energy_mj": self.popup.energy * self.newton_per_n,
                      "certified": self.popup.certified},
            "switched": {"apex_mm": self.final.apex_mm, "h_mm": kp_down.h_mm, "r_a_mm": kp_down.r_a_mm,
                         "z_a_mm": kp_down.z_a_mm, "r_b_mm": kp_down.r_b_mm, "z_b_mm": kp_down.z_b_mm,
                         "energy_mj": self.final.energy * self.newton_per_n,
                         "certified": self.final.certified},
            "curve": {"w_mm": self.w_mm.tolist(), "force_n": (self.force * self.newton_per_n).tolist()},
            "elapsed_s": self.elapsed_s,
        }


def _step(problem, y, w, radius):
    c = contact_solve(problem, y, w, radius, max_iter=STEP_MAX_ITER)
    return c, max(c.force, 0.0) if c.nodes else 0.0, problem.energy(c.y)


def _peak(ws, fs):
    """Vertex of the parabola through the largest sample and its neighbours (the sample itself
    at an end)."""
    i = int(np.argmax(fs))
    if i == 0 or i == len(fs) - 1:
        return float(fs[i]), float(ws[i])
    c = np.polyfit(ws[i - 1:i + 2], fs[i - 1:i + 2], 2)
    if c[0] >= 0:
        return float(fs[i]), float(ws[i])
    w = -c[1] / (2 * c[0])
    return float(np.polyval(c, w)), float(w)


def _barrier(W, F, E) -> float:
    """The largest elastic energy on the path: where F returns to 0, E is largest (dE = -F dw).
    Past the last sample in contact, F is extrapolated linearly to zero (within the next step,
    where contact was lost) and the energy continued by the work of that linear force (a
    sampled maximum alone would depend on the step)."""
    k = max(i for i, f in enumerate(F) if f > NO_FORCE) if max(F) > NO_FORCE else 0
    best = max(E[:k + 1])
    if 0 < k < len(F) - 1 and F[k - 1] > F[k] > NO_FORCE:
        dw = min(F[k] * (W[k - 1] - W[k]) / (F[k - 1] - F[k]), W[k] - W[k + 1])
        best = max(best, E[k] + 0.5 * F[k] * dw)
    return float(best)


def switching_path(patch: Patch, material: Material = DEFAULT_MATERIAL,
                   params: ShellParams = DEFAULT_SHELL, *, steps: int = 24,
                   hold_factor: float = HOLD_FACTOR) -> SwitchingPath:
    t0 = time.perf_counter()
    problem = held_problem(patch, material, params, hold_factor)
    up = popped_up(problem, patch, material)
    h = up.apex_mm
    if not up.certified or h - rim_mm(problem, up.y) <= 0.05:
        raise StitchSwitchError(f"d {patch.diameter_mm:g} mm, fill {patch.fill:g}: no certified "
                                "pop-up state in the frame, nothing to switch")
    radius = plate_radius_mm(patch.diameter_mm)
    ws = np.linspace(h, -DEPTH * h, steps + 1)
    states, W, F, E, A, C = [up.y], [h], [0.0], [up.energy], [h], [True]
    y = up.y
    step = ws[0] - ws[1]
    w = h
    while w > ws[-1] + 1e-12:
        for _ in range(MAX_HALVINGS + 1):
            trial = max(w - step, ws[-1])
            res, f, e = _step(problem, y, trial, radius)
            if res.converged:
                break
            step *= 0.5
        if not res.converged:               # the path cannot be followed further: stop here
            C.append(False)
            break
        w, y = trial, res.y
        states.append(y)
        W.append(w), F.append(f), E.append(e), C.append(True)
        A.append(float(problem.meridian.node_values(y)[2][0]))
        step = ws[0] - ws[1]
        if f <= NO_FORCE and max(F) > NO_FORCE:
            break
    # refine around the largest sampled force
    i = int(np.argmax(F))
    lo, hi = max(i - 1, 0), min(i + 1, len(W) - 1)
    rw, rf, re = [W[lo]], [F[lo]], [E[lo]]
    yr = states[lo]
    for w in np.linspace(W[lo], W[hi], 2 * REFINE + 1)[1:]:
        res, f, e = _step(problem, yr, w, radius)
        if not res.converged:            # only converged states give a force
            break
        yr = res.y
        rw.append(w), rf.append(f), re.append(e)
    fmax, wmax = _peak(np.array(rw), np.array(rf))
    if F[-1] <= NO_FORCE:
        # contact lost: the state is an unloaded equilibrium on the ridge between the two
        # basins; one more plate step, held on the apex only, starts the snap on the pushed side
        apex = problem.meridian.dof("inner", "z", 0)
        y = y.copy()
        y[apex] = W[-1] - SNAP_NUDGE * h
        y = minimize(problem.with_(pinned=[apex]), y, max_iter=STEP_MAX_ITER).y
    final = relax(problem, y)
    barrier = _barrier(W, F, E) - up.energy
    return SwitchingPath(
        patch=patch, plate_radius_mm=radius, w_mm=np.array(W), force=np.array(F),
        elastic_energy=np.array(E), apex_mm=np.array(A), converged=np.array(C),
        switching_force=fmax, w_switch_mm=wmax, barrier=float(barrier), popup=up, final=final,
        inverted=is_inverted(problem, final), newton_per_n=force_scale_n_per_model(material, params),
        elapsed_s=time.perf_counter() - t0)
