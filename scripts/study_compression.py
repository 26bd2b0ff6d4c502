"""Measure how the keypoints depend on the compressive response of the fabric (docs/model.md,
"Compression as physics"): the tables there are this script's output.

1. The printed model's limit: no jamming stretch (jam = 0), the barrier at zero length, h as
   the bare fabric's compressive ratio c_fab goes to zero (floor 1e-12).
2. The default material: the keypoints as the numerical floor goes to zero, the largest change
   per decade over the paper's 25 calibration designs, and how many solves certify.
3. h against the jamming stretch around the default's.

Usage: python scripts/study_compression.py [--quick]
"""
from __future__ import annotations

import argparse

import numpy as np

from stitchswitch import DEFAULT_MATERIAL, Patch, solve
from stitchswitch.reduced.calibration.designs import CALIBRATION_DESIGNS

KEYS = ("h_mm", "r_a_mm", "z_a_mm", "r_b_mm", "z_b_mm")


def keypoints(d, p, **changes):
    sol = solve(Patch(d, p), DEFAULT_MATERIAL.replace(**changes))
    return np.array([getattr(sol.keypoints, k) for k in KEYS]), sol.converged


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="fewer designs (a smoke run)")
    args = ap.parse_args()
    designs = list(CALIBRATION_DESIGNS)
    shown = [(20.0, 0.6), (40.0, 0.8), (90.0, 0.6), (70.0, 1.0)]
    if args.quick:
        designs = shown

    m = DEFAULT_MATERIAL
    print(f"default material: c_emb {m.c_emb:.4g}, c_fab {m.c_fab:g}, jam {m.jam:.4g}, "
          f"floor {m.compression_floor:g}")
    print("1. no jamming (jam = 0), floor 1e-12: h (mm) as c_fab -> 0; '!' = not certified")
    values = (1e-2, 1e-3, 1e-4, 1e-5)
    print("design      " + "".join(f"{v:>10g}" for v in values))
    for d, p in shown:
        row = [keypoints(d, p, c_fab=v, jam=0.0, compression_floor=1e-12) for v in values]
        print(f"d {d:3.0f} p {p:.1f} " + "".join(f"{k[0]:9.2f}{' ' if ok else '!'}" for k, ok in row))

    print("\n2. default material: largest change of each keypoint (mm) per decade of the floor")
    floors = (1e-5, 1e-6, 1e-7, 1e-8)
    table = {f: [keypoints(d, p, compression_floor=f) for d, p in designs] for f in floors}
    print("decade            " + "".join(f"{k:>8}" for k in KEYS) + "  certified (lower floor)")
    for a, b in zip(floors, floors[1:]):
        change = np.max([np.abs(x[0] - y[0]) for x, y in zip(table[a], table[b])], axis=0)
        ok = sum(y[1] for y in table[b])
        print(f"{a:g} -> {b:g}".ljust(18) + "".join(f"{v:8.4f}" for v in change) + f"  {ok}/{len(designs)}")

    print("\n3. h (mm) against the jamming stretch (default material otherwise)")
    jams = tuple(round(m.jam + dj, 3) for dj in (-0.1, 0.0, 0.1))
    print("design      " + "".join(f"{j:>8g}" for j in jams))
    for d, p in shown:
        row = [keypoints(d, p, jam=j) for j in jams]
        print(f"d {d:3.0f} p {p:.1f} " + "".join(f"{k[0]:7.2f}{' ' if ok else '!'}" for k, ok in row))


if __name__ == "__main__":
    main()
