"""Writes curve.png and curve.csv: the switch-force plot and CSV of the synthetic curve
(tests/switch_force_curve.py) as ``stitchswitch switch-force`` drew them in the CLI module,
before the drawing moved to ``fem_reference/snap/path_plot.py``; tests/test_switch_force_plot.py
proves the library writes the same bytes. Run once, at commit 7bf1021:
``PYTHONPATH=src python tests/data/switch_force/make_golden.py``."""
from __future__ import annotations

import pathlib
import sys

HERE = pathlib.Path(__file__).parent
sys.path.insert(0, str(HERE.parents[1]))


def main() -> None:
    from stitchswitch.cli.reference.switch_force import _write
    from switch_force_curve import synthetic_curve

    curve = synthetic_curve()
    tmp = {"--csv": HERE / "curve.csv", "--plot": HERE / "curve.png"}
    _write(tmp, curve, curve.force * curve.newton_per_n, {"verdict": "bistable"},
           curve.patch.diameter_mm, curve.patch.fill, 200.0)


if __name__ == "__main__":
    main()
