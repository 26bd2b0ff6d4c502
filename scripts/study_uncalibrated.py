"""How far each parameter that calibration does not fit moves the keypoints over its documented
plausible range (docs/model.md, "Sensitivity"): the table there is this script's output.

For each parameter in ``RANGES`` the default material is solved at the range's ends on the
paper's 25 calibration designs; reported is the largest change of each keypoint between the
default value and either end (mm), its median over the designs for h, and whether every solve
certified.

Usage: python scripts/study_uncalibrated.py [--workers N]
"""
from __future__ import annotations

import argparse

import numpy as np

from stitchswitch import DEFAULT_MATERIAL, Patch, solve
from stitchswitch.executor import run_all
from stitchswitch.reduced.calibration.designs import CALIBRATION_DESIGNS

KEYS = ("h_mm", "r_a_mm", "z_a_mm", "r_b_mm", "z_b_mm")

#: Parameter -> (low, high, why that range).
RANGES = {
    "compression_floor": (1e-7, 1e-5, "numerical: a decade either way of the default 1e-6"),
    "eta": (1.68, 1.72, "the hoop's pre-stretch, set to 1.7 to about +-1 % by the marked grid"),
    "domain_max_rb": (5.0, 10.0, "numerical: below d = 68 mm it sets the resolution (N_in >= "
                                 "299 / domain_max_rb) and the domain (at most that many R_b)"),
}


def _keypoints(job):
    (d, p), changes = job
    sol = solve(Patch(d, p), DEFAULT_MATERIAL.replace(**changes))
    return [getattr(sol.keypoints, k) for k in KEYS], bool(sol.converged and sol.second_order)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--workers", type=int, default=2)
    args = ap.parse_args(argv)
    designs = list(CALIBRATION_DESIGNS)
    base = run_all(_keypoints, [(dp, {}) for dp in designs], workers=args.workers)
    b = np.array([k for k, _ in base])
    print("| parameter | default | range | " + " | ".join(KEYS) + " | h, median | certified |")
    print("|---|---|---|" + "---|" * len(KEYS) + "---|---|")
    for name, (lo, hi, _) in RANGES.items():
        change, ok = np.zeros((len(designs), len(KEYS))), 0
        for value in (lo, hi):
            out = run_all(_keypoints, [(dp, {name: value}) for dp in designs], workers=args.workers)
            change = np.maximum(change, np.abs(np.array([k for k, _ in out]) - b))
            ok += sum(c for _, c in out)
        worst = change.max(axis=0)
        print(f"| {name} | {getattr(DEFAULT_MATERIAL, name):g} | [{lo:g}, {hi:g}] | "
              + " | ".join(f"{v:.3f}" for v in worst) + f" | {np.median(change[:, 0]):.3f} | "
              f"{ok}/{2 * len(designs)} |")
    for name, (_, _, why) in RANGES.items():
        print(f"* {name}: {why}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
