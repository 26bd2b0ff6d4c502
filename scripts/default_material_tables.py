"""The default material's tables in docs/model.md ("The default material"): its values, its
figures against the targets of its fit (``reduced.calibration.magnitudes``) and the predicted h
over a grid of designs, each with the rule that placed b (f flat, s steepest, n neck).

Usage: python scripts/default_material_tables.py
"""
from __future__ import annotations

from stitchswitch import DEFAULT_MATERIAL, Patch, solve
from stitchswitch.reduced.calibration import magnitudes
from stitchswitch.reduced.calibration.evolution import PARAMS

DIAMETERS_MM = (15.0, 20.0, 30.0, 40.0, 50.0, 60.0, 70.0, 90.0, 100.0)
FILLS = (0.5, 0.6, 0.7, 0.8, 0.9, 1.0)


def main() -> None:
    m = DEFAULT_MATERIAL
    print("| " + " | ".join(PARAMS) + " |")
    print("|" + "---|" * len(PARAMS))
    print("| " + " | ".join(f"{getattr(m, n):.4g}" for n in PARAMS) + " |")

    ev = magnitudes.evaluate(m)
    print("\n| mean over the 25 calibration designs (mm) | " + " | ".join(k[:-3] for k in magnitudes.KEYS) + " |")
    print("|---|" + "---|" * len(magnitudes.KEYS))
    print("| Table 1 implies *(paper)* | " + " | ".join(f"{magnitudes.TABLE1_MEANS_MM[k]:.2f}"
                                                     for k in magnitudes.KEYS) + " |")
    print("| default material | " + " | ".join(f"{ev.means_mm[k]:.2f}" for k in magnitudes.KEYS) + " |")
    print("| difference | " + " | ".join(f"{100 * (ev.means_mm[k] / magnitudes.TABLE1_MEANS_MM[k] - 1):+.1f} %"
                                         for k in magnitudes.KEYS) + " |")
    print(f"\nh(15 mm, 0.6) = {ev.flat_h_mm:.2f} mm; r_a - r_b at (90 mm, 1.0) = {ev.overhang_mm:.2f} mm; "
          f"h(90, 0.8) - h(60, 0.8) = {ev.growth_mm:.2f} mm; h(100, 1.0) = {ev.pocket_h_mm:.2f} mm; "
          f"largest eps_theta / gamma at the probed "
          f"designs {ev.limit_ratio:.3f}; uncertified solves {ev.uncertified}")

    print("\n| d \\ p | " + " | ".join(f"{p:g}" for p in FILLS) + " |")
    print("|---|" + "---|" * len(FILLS))
    for d in DIAMETERS_MM:
        cells = []
        for p in FILLS:
            kp = solve(Patch(d, p)).keypoints
            cells.append(f"{kp.h_mm:.2f} {kp.b_rule[0]}")
        print(f"| {d:g} | " + " | ".join(cells) + " |")


if __name__ == "__main__":
    main()
