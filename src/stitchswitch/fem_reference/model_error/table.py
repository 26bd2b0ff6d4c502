"""The model-error table: the reduced model (N = 300) against the shell of revolution, per
design and keypoint, with the gap attributed to the physics the reduced model leaves out.

For each design the shell is solved with every physics switch on (``ShellParams``), then once
with each switch of ``SWITCHES`` off, and once with all of them off (the shell with the reduced
model's physics, "base"). Reported per keypoint (mm): the shell's value, the reduced model's and
their gap, reduced - shell; per switch, the change of the shell's keypoint when that switch is
turned off (without - full: the part of the gap that physics accounts for, if the effects add);
and the remainder reduced - base, which no switch explains (the difference of formulation and
discretization: a shell continuum against 300 nodes, the interface as a double node). The sum
of the switch columns and the remainder differs from the gap by the switches' interaction,
reported as such. A keypoint passes when the gap is within ``budget.BUDGET``.
"""
from __future__ import annotations

from dataclasses import dataclass

from stitchswitch.fem_reference.model_error.budget import BUDGET, KEYS
from stitchswitch.fem_reference.revolution.params import DEFAULT_SHELL, SWITCHES, ShellParams
from stitchswitch.fem_reference.revolution.solve import equilibrium
from stitchswitch.reduced.model.params import DEFAULT_MATERIAL, Material, Patch

DEFAULT_DESIGNS = tuple((d, p) for d in (25.0, 50.0, 90.0) for p in (0.6, 0.8, 1.0))
REDUCED_NODES = 300


@dataclass(frozen=True)
class ShellRun:
    """One shell solve: its keypoints (mm), certificate (converged, strict minimum), energy."""

    keypoints_mm: dict
    certified: bool
    energy: float
    iterations: int
    solve_s: float

    def as_dict(self) -> dict:
        return {**self.keypoints_mm, "certified": self.certified, "energy": self.energy,
                "iterations": self.iterations, "solve_s": self.solve_s}


@dataclass(frozen=True)
class DesignError:
    diameter_mm: float
    fill: float
    reduced_mm: dict
    reduced_certified: bool
    shell: ShellRun
    without: dict           # switch -> ShellRun
    base: ShellRun

    def gap_mm(self, key: str) -> float:
        return self.reduced_mm[key] - self.shell.keypoints_mm[key]

    def attribution_mm(self, switch: str, key: str) -> float:
        return self.without[switch].keypoints_mm[key] - self.shell.keypoints_mm[key]

    def remainder_mm(self, key: str) -> float:
        return self.reduced_mm[key] - self.base.keypoints_mm[key]

    def interaction_mm(self, key: str) -> float:
        return self.gap_mm(key) - self.remainder_mm(key) - sum(
            self.attribution_mm(s, key) for s in SWITCHES)

    def within_budget(self, key: str) -> bool:
        return BUDGET[key].allows(self.gap_mm(key), self.shell.keypoints_mm[key])

    @property
    def certified(self) -> bool:
        return bool(self.reduced_certified and self.shell.certified and self.base.certified
                    and all(r.certified for r in self.without.values()))

    def as_dict(self) -> dict:
        return {"d_mm": self.diameter_mm, "fill": self.fill, "reduced": dict(self.reduced_mm),
                "reduced_certified": self.reduced_certified, "shell": self.shell.as_dict(),
                "without": {s: r.as_dict() for s, r in self.without.items()},
                "base": self.base.as_dict(), "certified": self.certified,
                "gap_mm": {k: self.gap_mm(k) for k in KEYS},
                "attribution_mm": {s: {k: self.attribution_mm(s, k) for k in KEYS} for s in SWITCHES},
                "remainder_mm": {k: self.remainder_mm(k) for k in KEYS},
                "interaction_mm": {k: self.interaction_mm(k) for k in KEYS},
                "within_budget": {k: self.within_budget(k) for k in KEYS}}


@dataclass(frozen=True)
class ModelErrorTable:
    rows: tuple[DesignError, ...]
    params: ShellParams

    def passed(self, key: str) -> bool:
        return all(r.within_budget(key) for r in self.rows)

    @property
    def all_passed(self) -> bool:
        return all(self.passed(k) for k in KEYS) and all(r.certified for r in self.rows)

    def as_dict(self) -> dict:
        from dataclasses import asdict

        return {"rows": [r.as_dict() for r in self.rows], "shell_params": asdict(self.params),
                "budget": {k: v.as_dict() for k, v in BUDGET.items()},
                "passed": {k: self.passed(k) for k in KEYS}, "all_passed": self.all_passed}


def _run(patch, material, params) -> ShellRun:
    st = equilibrium(patch, material, params)
    kp = st.keypoints
    return ShellRun({k: float(getattr(kp, k)) for k in KEYS}, st.certified, st.energy,
                    st.iterations, st.solve_s)


def design_error(patch: Patch, material: Material = DEFAULT_MATERIAL,
                 params: ShellParams = DEFAULT_SHELL) -> DesignError:
    from stitchswitch.reduced.solvers.solve import solve

    red = solve(patch, material.replace(n_nodes=REDUCED_NODES,
                                        dr_max_mm=material.dr_max_mm * material.n_nodes / REDUCED_NODES))
    kp = red.keypoints
    shell = _run(patch, material, params)
    # a switch that is already off changes nothing: its run is the full one
    without = {s: shell if params.without(s) == params else _run(patch, material, params.without(s))
               for s in SWITCHES}
    return DesignError(
        diameter_mm=patch.diameter_mm, fill=patch.fill,
        reduced_mm={k: float(getattr(kp, k)) for k in KEYS}, reduced_certified=red.certified,
        shell=shell, without=without, base=_run(patch, material, params.reduced_like()))


def model_error(designs=DEFAULT_DESIGNS, material: Material = DEFAULT_MATERIAL,
                params: ShellParams = DEFAULT_SHELL) -> ModelErrorTable:
    return ModelErrorTable(tuple(design_error(Patch(d, p), material, params) for d, p in designs), params)
