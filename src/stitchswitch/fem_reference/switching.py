"""Switching force from the shell reference: the apex is pushed from pop-up to pop-down.

The apex height w = z(0) is prescribed (the outer edge stays at z(L) = 0, as the fabric held in
the experiment) and stepped from the pop-up equilibrium h down through zero; at every step the
shell is re-solved from the previous step (displacement control follows snap-through, where a
force-controlled test jumps). The reaction F(w) = dE/dw is the force on the apex. The switching
force is the largest |F| before F changes sign (past it the patch snaps over by itself), and the
energy barrier is the integral of F from the pop-up state to that sign change. By the z -> -z
symmetry E(w) = E(-w), so F(0) = 0 and the path from h to 0 is half of the switch; with
displacement control the path did not fold back on the designs tried, so no arc-length
continuation is used (a step that fails to converge is reported, not hidden).

Units: the energy is the reduced model's (uncalibrated) scale, so F and the barrier are in
model units. Only trends and ratios between designs are meaningful (Appendix B measured 0.04 to
0.77 N with a contact plate; the mapping to newtons is a calibration not made here).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from stitchswitch.fem_reference.shell import ShellModel
from stitchswitch.reduced.model.params import DEFAULT_MATERIAL, Material, Patch


@dataclass(frozen=True)
class SwitchingCurve:
    patch: Patch
    w_mm: np.ndarray           # prescribed apex height, from h down
    force: np.ndarray          # reaction dE/dw (model units)
    converged: np.ndarray      # per step
    switching_force: float     # max |F| before the sign change
    barrier: float             # integral of F dw from h to the sign change (model units)
    w_snap_mm: float           # where F changes sign

    def as_dict(self) -> dict:
        return {"d_mm": self.patch.diameter_mm, "fill": self.patch.fill,
                "switching_force": self.switching_force, "energy_barrier": self.barrier,
                "w_snap_mm": self.w_snap_mm, "h_mm": float(self.w_mm[0]),
                "all_converged": bool(self.converged.all())}


#: Newton iterations per prescribed apex height: the steps close to w = 0 squeeze the patch
#: through the flat state and need more than the others (94 at d 40 mm, p 0.9, step 11 of 12).
STEP_MAX_ITER = 200


def switching_curve(patch: Patch, material: Material = DEFAULT_MATERIAL, *, steps: int = 40,
                    elements_inside: int = 30) -> SwitchingCurve:
    """F(w) from the pop-up equilibrium (w = h) down to w = 0 in ``steps`` steps."""
    from stitchswitch.reduced.solvers.solve import solve

    red = solve(patch, material)
    model = ShellModel(patch, material, elements_inside=elements_inside, growth=1.1)
    x = model.solve(model.start_from_profile(red.R_mm, red.r_mm, red.z_mm))._x
    apex = model.n + model._value_dofs[0]
    h = float(x[apex])
    free_all = model.free
    model.free = np.setdiff1d(free_all, [apex])              # the apex is now prescribed
    ws, fs, ok = [], [], []
    w_prev = h
    for w in np.linspace(h, 0.0, steps + 1):
        x = x.copy()
        # predictor: scale the whole height field (values and slopes) with the apex, which
        # keeps it smooth and z(L) = 0; Newton then restores equilibrium
        x[model.n:] *= w / w_prev if w_prev else 1.0
        x[apex] = w
        w_prev = w
        sol = model.solve(x, max_iter=STEP_MAX_ITER)
        x = sol._x
        _, g, _ = model.derivatives(x)
        ws.append(w)
        fs.append(float(g[apex]))
        ok.append(sol.converged)
    model.free = free_all
    w, f = np.array(ws), np.array(fs)
    # E(w) = E(-w) (the z -> -z symmetry), so F(0) = 0: the path from h to 0 is half of the
    # switch. The patch snaps where F first changes sign (or reaches 0, at w = 0).
    resisting = f[1:] < 0
    k = int(np.argmin(resisting)) + 1 if not resisting.all() else f.size - 1
    barrier = float(np.trapezoid(f[:k + 1], w[:k + 1]))          # = E(w_snap) - E(h)
    return SwitchingCurve(patch, w, f, np.array(ok), float(np.max(np.abs(f[:k + 1]))), barrier,
                          float(w[k]))
