"""A material fitted to the magnitudes the paper reports, when its samples are not available.

The paper's Table 1 gives, for the training set, the mean absolute error (mm) and the mean
percentage error of each keypoint. Their ratio is the mean measured value of that keypoint over
the 25 calibration designs (MAE / relative error, ``TABLE1_MEANS_MM``): h 9.8, r_a 19.3,
z_a 5.3, r_b 17.2, z_b 4.1 mm. ``fit_magnitudes`` fits a material to those five means and to the
paper's qualitative findings, with the same search space, differential evolution and polish as
``evolution.calibrate``:

    objective = mean over the residuals of
        (mean predicted keypoint - target) / target           five means, relative
        near-flat small sparse patch: h(15 mm, 0.6) <= 1 mm   (hinge, relative to target h)
        h grows with d: h(90 mm, 0.8) - h(60 mm, 0.8) >= 1 mm  (hinge, relative to target h)
        the tennis pocket is reachable: h(100 mm, 1.0) >= 18 mm (the paper's pocket stood
            17.5 mm high; hinge, relative to target h)
        overhang at high fill: r_a - r_b >= 1 mm at (90 mm, 1.0)   (hinge, relative to r_b)
        hardening below its limit: eps/gamma <= ``HARDENING_MARGIN`` at the probed designs
        stitched mats at least as stiff as bare knit: log10(k_fab / k_emb) <= 0 for the
            bending, radial and hoop pairs (``STIFFER``)
        a weak pull towards the starting material (``PRIOR_WEIGHT`` per search coordinate)

Five means do not determine ten parameters; the pull picks, among the materials that meet the
targets, the one nearest the start, so the fit is reproducible. The result is a
**paper-magnitude** material: its keypoints have the paper's sizes, but it is not fitted to any
fabricated sample.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np

from stitchswitch.errors import InvalidInputError
from stitchswitch.reduced.calibration import evolution as cal
from stitchswitch.reduced.calibration.designs import CALIBRATION_DESIGNS
from stitchswitch.reduced.model.params import Material, Patch

#: Table 1 (training set): (MAE mm, mean percentage error) per keypoint.
TABLE1_TRAIN = {"h_mm": (1.44, 14.7), "r_a_mm": (0.87, 4.5), "z_a_mm": (1.09, 20.4),
                "r_b_mm": (1.05, 6.1), "z_b_mm": (0.93, 22.9)}
#: The mean measured keypoints those pairs imply: MAE / (percentage / 100).
TABLE1_MEANS_MM = {k: mae / (pct / 100.0) for k, (mae, pct) in TABLE1_TRAIN.items()}
KEYS = tuple(TABLE1_MEANS_MM)

#: Largest eps_theta / gamma the fit allows at the probed designs (the continuation starts at 0.99).
HARDENING_MARGIN = 0.9
#: Weight of the pull towards the starting material, per search coordinate.
PRIOR_WEIGHT = 0.05
#: The small, sparse design that must stay near flat, and its height limit (mm).
FLAT_DESIGN, FLAT_H_MM = (15.0, 0.6), 1.0
#: Two designs of one fill, and how much taller the larger must be (mm).
GROWTH_DESIGNS, GROWTH_MM = ((60.0, 0.8), (90.0, 0.8)), 1.0
#: The largest, densest design and the height it must reach: the paper's pocket measured 17.5 mm.
POCKET_DESIGN, POCKET_H_MM = (100.0, 1.0), 18.0
#: The dense design that must overhang, and the least r_a - r_b there (mm).
OVERHANG_DESIGN, OVERHANG_MM = (90.0, 1.0), 1.0
#: Pairs (embroidered, bare) of which the embroidered must not be the softer.
STIFFER = (("w_b_emb", "w_b_fab"), ("k_r_emb", "k_r_fab"), ("k_theta_emb", "k_theta_fab"))
#: Where the hardening limit is checked besides the calibration designs: the map's largest, densest.
HARDENING_DESIGNS = ((100.0, 1.0), (100.0, 0.5))


@dataclass(frozen=True)
class Evaluation:
    """A material's figures against the targets."""

    means_mm: dict
    flat_h_mm: float
    overhang_mm: float
    limit_ratio: float
    growth_mm: float
    pocket_h_mm: float
    uncertified: int

    def within(self, tolerance: float) -> bool:
        return all(abs(self.means_mm[k] / TABLE1_MEANS_MM[k] - 1.0) <= tolerance for k in KEYS)


def evaluate(material: Material) -> Evaluation:
    """Mean keypoints over the calibration designs and the qualitative figures of ``material``."""
    from stitchswitch.reduced.model.discretization import make_grid
    from stitchswitch.reduced.model.terms.hardening import limit_ratio
    from stitchswitch.reduced.solvers.solve import solve

    kps, ratio, bad = {}, 0.0, 0
    designs = CALIBRATION_DESIGNS + (FLAT_DESIGN, POCKET_DESIGN) + GROWTH_DESIGNS + HARDENING_DESIGNS
    for d, p in dict.fromkeys(designs):
        patch = Patch(d, p)
        sol = solve(patch, material)
        bad += not sol.certified
        kps[(d, p)] = sol.keypoints
        ratio = max(ratio, limit_ratio(make_grid(patch, material), sol.r_mm / sol.dr_mm))
    means = {k: float(np.mean([getattr(kps[dp], k) for dp in CALIBRATION_DESIGNS])) for k in KEYS}
    big = kps[OVERHANG_DESIGN]
    small, large = (kps[dp].h_mm for dp in GROWTH_DESIGNS)
    return Evaluation(means, kps[FLAT_DESIGN].h_mm, big.r_a_mm - big.r_b_mm, ratio, large - small,
                      kps[POCKET_DESIGN].h_mm, bad)


@dataclass(frozen=True)
class MagnitudeObjective:
    """Picklable objective: x (``evolution``'s search space) -> mean of ``residuals(x)`` squared."""

    base: Material
    free: tuple
    x_start: tuple

    def __call__(self, x) -> float:
        return float(np.mean(self.residuals(x) ** 2))

    def residuals(self, x) -> np.ndarray:
        x = np.asarray(x, dtype=float)
        prior = PRIOR_WEIGHT * (x - np.asarray(self.x_start))
        try:
            material = cal._from_x(x, self.free, self.base)
            ev = evaluate(material)
        except InvalidInputError:
            return np.concatenate([np.full(len(KEYS) + 5 + len(STIFFER), 10.0), prior])
        res = [ev.means_mm[k] / TABLE1_MEANS_MM[k] - 1.0 for k in KEYS]
        res.append(max(0.0, ev.flat_h_mm - FLAT_H_MM) / TABLE1_MEANS_MM["h_mm"])
        res.append(max(0.0, GROWTH_MM - ev.growth_mm) / TABLE1_MEANS_MM["h_mm"])
        res.append(max(0.0, POCKET_H_MM - ev.pocket_h_mm) / TABLE1_MEANS_MM["h_mm"])
        res.append(max(0.0, OVERHANG_MM - ev.overhang_mm) / TABLE1_MEANS_MM["r_b_mm"])
        res.append(10.0 * max(0.0, ev.limit_ratio - HARDENING_MARGIN) + math.sqrt(ev.uncertified))
        res.extend(max(0.0, math.log10(getattr(material, fab) / getattr(material, emb)))
                   for emb, fab in STIFFER)
        return np.concatenate([res, prior])


@dataclass(frozen=True)
class MagnitudeFit:
    material: Material
    objective: float
    evaluation: Evaluation
    evaluations: int
    elapsed_s: float


def fit_magnitudes(start: Material, *, maxiter: int = 20, popsize: int = 8, seed: int = 0,
                   executor=None, free=None, label: str = "") -> MagnitudeFit:
    """Differential evolution and polish of ``MagnitudeObjective`` from ``start`` (module
    docstring); ``label`` is written into the fitted material."""
    free = tuple(free or cal.DEFAULT_FREE)
    bounds = cal._search_bounds(free)
    x0 = cal.start_point(cal._to_x(start.as_dict(), free), bounds)
    objective = MagnitudeObjective(start, free, tuple(x0))
    t0 = time.perf_counter()
    res = cal.evolve(objective, bounds, x0, maxiter=maxiter, popsize=popsize, seed=seed, tol=1e-8,
                     executor=executor)
    x, f, used = cal.polish_fit(objective, res.x, float(res.fun), bounds)
    material = cal._from_x(x, free, start).replace(label=label)
    return MagnitudeFit(material, f, evaluate(material), int(res.nfev) + used, time.perf_counter() - t0)
