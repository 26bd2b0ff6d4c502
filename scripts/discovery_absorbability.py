"""Re-measure the absorbability table of docs/discovery.md and the hidden ranges it implies.

For every library effect (and the control ``gravity_sag``) at a sweep of strengths: noise-free
keypoints of the true model (``validation.discovery.synthetic``, the paper's 25 training
designs), the starting model (the default material without hardening) recalibrated on them as
the workflow's step 1 does (``validation.discovery.synthetic.unabsorbed``), and the MSE it leaves,
i.e. what no recalibration removes. Against the reference noise (mean sigma^2 per keypoint,
``SIGMA_MM``) that is chi2 = RSS_clean / sigma^2 (125 residuals), the oracle F test's
noncentrality; its power at the workflow's alpha / 6 is printed beside it.

The documented criterion for a hidden range (``EffectParameter.hidden``) is that the
unabsorbable part be comparable to the noise, chi2 of about 25 or more. Applied to the sweep
(on the sign of the documented range for a signed effect): the range runs from the smallest
swept strength with chi2 >= ``CHI2_LOW`` (25) up to the last strength before chi2 first
exceeds ``CHI2_HIGH`` (100, about where the earlier ranges ended), within the bounds; an
effect that never reaches 25 inside its bounds has no such range (printed as such).

    python scripts/discovery_absorbability.py [--effects a,b] [--json]

Deterministic (seeded designs, certified solves); about 15 minutes of one core.
"""
from __future__ import annotations

import argparse
import json
import sys

import numpy as np

CHI2_LOW, CHI2_HIGH = 25.0, 100.0
#: Swept strengths per effect (inside the fit bounds).
SWEEP = {
    "hardening": (0.5, 1.0, 2.0, 3.0, 4.0, 4.75),
    "hoop_bending": (0.25, 0.5, 1.0, 2.0, 3.0, 5.0, 10.0, 20.0),
    "tension_asymmetry": (-0.005, -0.0075, -0.01, -0.015, -0.02, -0.03, -0.04, -0.05, -0.06, -0.08, 0.05, 0.1),
    "prestretch_loss": (0.1, 0.2, 0.3, 0.4, 0.5, 0.6),
    "fill_exponent": (-1.4, -1.0, -0.5, 0.5, 1.0, 1.5, 2.0, 2.5, 2.85),
    "boundary_transition": (2.0, 4.0, 6.0, 8.0, 10.0, 11.4),
    "gravity_sag": (2.5e-7, 5e-7, 1e-6, 2e-6, 5e-6, 1e-5),
}


def measure(effect: str, strengths) -> list[dict]:
    from stitchswitch.validation.discovery.cv import oracle_power
    from stitchswitch.validation.discovery.effects import LIBRARY
    from stitchswitch.validation.discovery.space import BASE_FREE
    from stitchswitch.validation.discovery.synthetic import (
        SIGMA_MM,
        START_MATERIAL,
        paper_designs,
        true_keypoints,
        unabsorbed,
    )
    from stitchswitch.validation.discovery.workflow import DiscoveryConfig

    config = DiscoveryConfig()
    train, _ = paper_designs(np.random.default_rng(0))
    sigma2 = float(np.mean(np.square(SIGMA_MM)))
    rows = []
    for v in strengths:
        clean, bad = true_keypoints(train, effect, (float(v),))
        r = unabsorbed(train, clean, START_MATERIAL, config=config)
        chi2 = r["rss_clean_mm2"] / sigma2
        rows.append({"effect": effect, "strength": float(v), "mse_mm2": r["mse_clean_mm2"],
                     "chi2": chi2, "unsolved": bad,
                     "power": oracle_power(chi2, clean.size, len(BASE_FREE) + 1,
                                           config.alpha / len(LIBRARY))})
        print(f"{effect} {v:g}: MSE {r['mse_clean_mm2']:.3f} mm^2, chi2 {chi2:.1f}",
              file=sys.stderr, flush=True)
    return rows


def hidden_range(effect: str, rows: list[dict]):
    """(low, high) by the criterion of the module docstring, or None."""
    from stitchswitch.validation.discovery.effects import resolve

    par = resolve(effect).parameters[0]
    sign = -1.0 if par.hidden[1] < 0 else 1.0
    side = sorted((r for r in rows if r["strength"] * sign > 0), key=lambda r: abs(r["strength"]))
    start = next((j for j, r in enumerate(side) if r["chi2"] >= CHI2_LOW), None)
    if start is None:
        return None
    top = side[start]
    for r in side[start + 1:]:
        if r["chi2"] > CHI2_HIGH:
            break
        top = r
    pair = sorted((side[start]["strength"], top["strength"]))
    return tuple(pair)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--effects", default=",".join(SWEEP))
    ap.add_argument("--json", action="store_true")
    args = ap.parse_args(argv)
    names = [n for n in args.effects.split(",") if n]
    bad = [n for n in names if n not in SWEEP]
    if bad:
        ap.error(f"--effects: {', '.join(bad)} not in {', '.join(SWEEP)}")
    out = {}
    for name in names:
        rows = measure(name, SWEEP[name])
        out[name] = {"rows": rows, "hidden_range": hidden_range(name, rows)}
    if args.json:
        print(json.dumps(out, indent=1))
        return 0
    print("| effect | strength | MSE left after recalibration (mm^2) | chi2 | oracle power |")
    print("|---|---|---|---|---|")
    for name, r in out.items():
        for row in r["rows"]:
            print(f"| {name} | {row['strength']:g} | {row['mse_mm2']:.3f} | {row['chi2']:.1f} | "
                  f"{row['power']:.2f} |")
    print()
    for name, r in out.items():
        rng = r["hidden_range"]
        print(f"{name}: " + (f"chi2 25-100 at {rng[0]:g} to {rng[1]:g}" if rng else
                             "chi2 stays below 25 inside the bounds"))
    return 0


if __name__ == "__main__":
    sys.exit(main())
