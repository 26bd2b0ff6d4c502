"""Sensitivity of the keypoints to the material parameters, over a set of designs.

For a design (d, p), a parameter theta and a keypoint q (h, r_a, z_a, r_b, z_b), by central
differences in log theta with step s (theta times exp(+s) and exp(-s)):

    dq/dlog theta = (q+ - q-) / 2s   (mm: always defined),
    elasticity    = (dq/dlog theta) / q0   (dimensionless: (dq/q) / (dtheta/theta)),

the elasticity being undefined where ``|q0| < UNDEFINED_BELOW_MM`` (h of a flat patch). The
base design is a cold solve (``solve``'s own result); each perturbed solve is warm-started from
it, so the derivative follows the branch the base sits on.

Why s = 0.05 (``DEFAULT_STEP``). The keypoints are certified to far better than 1e-6 mm, so a
small step is not limited by solver noise but by the model's discrete parts: b is a node of
the profile (``keypoints``), and with ``eta`` the number of nodes inside the patch changes
(for d >= 68 mm). A 5 % change of a parameter is a plausible calibration uncertainty, and the
central-difference error is O(s^2) (0.25 % of the curvature term). Because the equilibrium
can switch branch or b can jump a node, a derivative is **flagged** instead of reported when

* a perturbed solve is not certified (``FLAG_NOT_CONVERGED``; or the base one,
  ``FLAG_BASE``), or the perturbed material is invalid (``FLAG_OUT_OF_RANGE``, e.g. eta past 3);
* the forward and backward one-sided estimates disagree (``FLAG_NOT_SMOOTH``):
  ``|q+ - 2 q0 + q-| > SMOOTH_RTOL max(|q+ - q0|, |q0 - q-|) + SMOOTH_ATOL_MM``, i.e. the two
  one-sided slopes differ by more than half the larger one (plus 0.02 mm of change). A smooth
  q ~ theta^a has a relative disagreement of about ``a s``, a few percent. What this catches
  (measured with the default material): b moving to the next node (z_b steps of 0.3-0.5 mm),
  kinks of h where the profile's active set changes (the onset of an overhang, where h's
  slope in log eta drops from 14 to 1.5 mm), and the discretization's steps with eta,
  dr_max_mm and domain_max_rb. A strongly curved but smooth response over theta e^(+-s)
  (h near its maximum in eta) is flagged too: no single slope describes it over that range.
  Where b moves a node on both sides, the slope of z_b and r_b includes those steps.

Which parameters: every ``float`` field of ``Material`` (derived from the dataclass, so a new
field is included automatically), less the numerical ones in ``NUMERICAL`` unless asked for.
``n_nodes`` is an integer and cannot be scaled by exp(s). A parameter that is 0 (w_log may be)
stays 0 under the log step, so its derivatives are exactly 0: theta dq/dtheta vanishes there.

The summary (``SummaryRow``) gives per (parameter, keypoint) the median and max of |elasticity|
over the designs where it is defined and not flagged, the same of |dq/dlog theta| in mm, and the
count of flagged designs. Parallel work goes through ``executor.run_all`` (results in order, so
parallel and serial runs are identical).
"""
from __future__ import annotations

import math
import typing
from dataclasses import dataclass, fields

import numpy as np

from stitchswitch.errors import InvalidInputError
from stitchswitch.reduced.calibration.designs import CALIBRATION_DESIGNS
from stitchswitch.reduced.model.params import Material, Patch

#: Float fields of Material that set the discretization, not the physics.
NUMERICAL = ("dr_max_mm", "domain_max_rb", "compression_floor")
KEYPOINTS = ("h_mm", "r_a_mm", "z_a_mm", "r_b_mm", "z_b_mm")

DEFAULT_STEP = 0.05
#: |q0| below this (mm): the elasticity is undefined; dq/dlog theta is still reported.
UNDEFINED_BELOW_MM = 0.05
SMOOTH_RTOL = 0.5
SMOOTH_ATOL_MM = 0.02

FLAG_BASE = "base not converged"
FLAG_NOT_CONVERGED = "not converged"
FLAG_OUT_OF_RANGE = "out of range"
FLAG_NOT_SMOOTH = "not smooth"


def check_step(step) -> float:
    """``step`` as a float; InvalidInputError unless it is a number in (0, 0.5]."""
    if isinstance(step, bool) or not isinstance(step, (int, float)) or not 0.0 < step <= 0.5:
        raise InvalidInputError(f"step: {step!r} is outside (0, 0.5]")
    return float(step)


def parameter_names(include_numerical: bool = False) -> tuple[str, ...]:
    """The float fields of ``Material``, less ``NUMERICAL`` unless ``include_numerical``."""
    hints = typing.get_type_hints(Material)
    return tuple(f.name for f in fields(Material) if hints[f.name] is float
                 and (include_numerical or f.name not in NUMERICAL))


@dataclass(frozen=True)
class Derivative:
    """One design, one parameter, one keypoint: the base value ``value_mm``, ``dq_dlog_mm``
    (nan if flagged), ``elasticity`` (nan if flagged or undefined) and ``flag`` ("" if none)."""

    diameter_mm: float
    fill: float
    parameter: str
    keypoint: str
    value_mm: float
    dq_dlog_mm: float
    elasticity: float
    flag: str

    def as_dict(self) -> dict:
        return {"d_mm": self.diameter_mm, "fill": self.fill, "parameter": self.parameter,
                "keypoint": self.keypoint, "value_mm": self.value_mm,
                "dq_dlog_mm": self.dq_dlog_mm, "elasticity": self.elasticity, "flag": self.flag}


@dataclass(frozen=True)
class SummaryRow:
    """One (parameter, keypoint) over the designs: medians and maxima of the absolute values
    (nan when no design has one), ``n_flagged`` designs left out, ``n_undefined`` designs
    with |q0| too small for an elasticity."""

    parameter: str
    keypoint: str
    n_designs: int
    n_flagged: int
    n_undefined: int
    median_abs_elasticity: float
    max_abs_elasticity: float
    median_abs_dq_dlog_mm: float
    max_abs_dq_dlog_mm: float

    def as_dict(self) -> dict:
        return dict(self.__dict__)


@dataclass(frozen=True)
class Sensitivity:
    """The sensitivity table of ``material`` over ``designs`` [(d_mm, fill)]: ``rows`` in the
    order parameter x keypoint, ``derivatives`` in the order design x parameter x keypoint."""

    material: Material
    step: float
    designs: tuple
    parameters: tuple
    rows: tuple
    derivatives: tuple
    n_solves: int

    def row(self, parameter: str, keypoint: str) -> SummaryRow:
        return next(r for r in self.rows if (r.parameter, r.keypoint) == (parameter, keypoint))

    def as_dict(self) -> dict:
        return {"material": self.material.as_dict(), "step": self.step,
                "designs": [{"d_mm": d, "fill": p} for d, p in self.designs],
                "parameters": list(self.parameters), "keypoints": list(KEYPOINTS),
                "n_solves": self.n_solves, "rows": [r.as_dict() for r in self.rows],
                "derivatives": [x.as_dict() for x in self.derivatives]}


def _keypoints(sol) -> tuple:
    kp = sol.keypoints
    return tuple(getattr(kp, q) for q in KEYPOINTS)


def _certified(sol) -> bool:
    return sol.converged and sol.second_order is not False


@dataclass(frozen=True)
class _DesignJob:
    """Picklable work item: one design -> per parameter (flag, (q0, q+, q-) or None), n solves."""

    material: Material
    parameters: tuple
    step: float

    def __call__(self, design) -> tuple[list, int]:
        from stitchswitch.reduced.solvers.solve import solve

        patch = Patch(*design)
        base = solve(patch, self.material)
        if not _certified(base):
            return [(FLAG_BASE, None)] * len(self.parameters), 1
        out, n = [], 1
        for name in self.parameters:
            theta = getattr(self.material, name)
            try:
                perturbed = [self.material.replace(**{name: theta * math.exp(s)})
                             for s in (self.step, -self.step)]
            except InvalidInputError:
                out.append((FLAG_OUT_OF_RANGE, None))
                continue
            sols = [solve(patch, m, warm_start=base) for m in perturbed]
            n += 2
            if not all(_certified(s) for s in sols):
                out.append((FLAG_NOT_CONVERGED, None))
                continue
            out.append(("", (_keypoints(base), *(_keypoints(s) for s in sols))))
        return out, n


def _derivative(design, parameter, k, flag, values, step) -> Derivative:
    """The central difference of keypoint ``k`` from (q0, q+, q-), or the flag."""
    nan = math.nan
    if values is None:
        return Derivative(*design, parameter, KEYPOINTS[k], nan, nan, nan, flag)
    q0, qp, qm = (v[k] for v in values)
    if abs(qp - 2.0 * q0 + qm) > SMOOTH_RTOL * max(abs(qp - q0), abs(q0 - qm)) + SMOOTH_ATOL_MM:
        return Derivative(*design, parameter, KEYPOINTS[k], q0, nan, nan, FLAG_NOT_SMOOTH)
    slope = (qp - qm) / (2.0 * step)
    elasticity = slope / q0 if abs(q0) >= UNDEFINED_BELOW_MM else nan
    return Derivative(*design, parameter, KEYPOINTS[k], q0, slope, elasticity, "")


def _median_max(values) -> tuple[float, float]:
    a = np.abs(np.array([v for v in values if math.isfinite(v)]))
    return (float(np.median(a)), float(a.max())) if a.size else (math.nan, math.nan)


def _summary(derivatives, parameter, keypoint) -> SummaryRow:
    mine = [x for x in derivatives if (x.parameter, x.keypoint) == (parameter, keypoint)]
    ok = [x for x in mine if not x.flag]
    return SummaryRow(parameter, keypoint, len(mine), len(mine) - len(ok),
                      sum(not math.isfinite(x.elasticity) for x in ok),
                      *_median_max(x.elasticity for x in ok),
                      *_median_max(x.dq_dlog_mm for x in ok))


def sensitivity(material: Material, designs=CALIBRATION_DESIGNS, step: float = DEFAULT_STEP, *,
                parameters=None, workers: int = 1, scheduler: str | None = None,
                progress=None) -> Sensitivity:
    """The sensitivity table of ``material`` (see the module docstring).

    ``designs``: [(diameter_mm, fill)]; ``parameters``: names of float fields of ``Material``
    (default ``parameter_names()``); ``workers``/``scheduler``: ``executor.make_executor``;
    ``progress(n_designs_done)`` after each design. Raises InvalidInputError for an empty or
    invalid design list, a step outside (0, 0.5] or an unknown parameter."""
    from stitchswitch.executor import run_all

    step = check_step(step)
    patches = [Patch(d, p) for d, p in designs]
    designs = tuple((x.diameter_mm, x.fill) for x in patches)
    if not designs:
        raise InvalidInputError("designs: at least one design is needed")
    allowed = parameter_names(include_numerical=True)
    parameters = parameter_names() if parameters is None else tuple(parameters)
    unknown = [n for n in parameters if n not in allowed]
    if unknown or not parameters:
        raise InvalidInputError(f"parameters: {', '.join(unknown) or 'none given'} "
                                f"(choose from {', '.join(allowed)})")
    results = run_all(_DesignJob(material, parameters, step), designs, workers=workers,
                      progress=progress, scheduler=scheduler)
    derivatives = tuple(_derivative(design, name, k, flag, values, step)
                        for design, (per_param, _) in zip(designs, results)
                        for name, (flag, values) in zip(parameters, per_param)
                        for k in range(len(KEYPOINTS)))
    rows = tuple(_summary(derivatives, name, q) for name in parameters for q in KEYPOINTS)
    return Sensitivity(material, step, designs, parameters, rows, derivatives,
                       sum(n for _, n in results))
