"""Writes golden.json: the hoop-placement results of the code before the feasible box of a set
of patches was one helper (``check.rules.hoopable.feasible_box``), recorded so that
tests/test_hoop_box.py can prove the refactoring changed nothing.

Run once, at commit 7bf1021 (``_placeable`` in ``fabrication/hoop_reason.py`` and
``_positions_on_grid`` in ``grouping/candidates.py`` still computing the box each their own
way): ``PYTHONPATH=src python tests/data/hoop_box/make_golden.py``. The cases are the two demo
designs (their design files, saved from ``stitchswitch.demos``, are beside this script) and
random patches on a rectangle and on the stretched skirt panel; the recorded values are every
candidate placement (hoop, turn, centre, held patches), ``_placeable`` for every candidate's
held set in every hoop and turn, with and without the piece, and the reason of each hooping of
the garment grouping.
"""
from __future__ import annotations

import json
import pathlib
import sys

import numpy as np

HERE = pathlib.Path(__file__).parent
sys.path.insert(0, str(HERE.parents[1]))             # tests/ for the cases


def main() -> None:
    from hoop_box_cases import cases
    from stitchswitch.layout.check.rules import hoopable
    from stitchswitch.layout.fabrication.grouping import candidates
    from stitchswitch.layout.fabrication.grouping.group import group
    from stitchswitch.layout.fabrication.hoop_reason import _placeable, hoop_reason

    out = {}
    for name, (feet, pieces, hoops) in cases(HERE).items():
        c = candidates.generate(feet, pieces, hoops)
        x = np.array([f.centre_mm for f in feet], dtype=float)
        r = np.array([f.radius_mm for f in feet], dtype=float)
        placeable = []
        for j in range(len(c)):
            held = np.flatnonzero(c.holds[j])
            piece = pieces[c.piece_index[j]]
            region = hoopable.hoop_region(piece.outline_mm, piece.blank_mm)
            placeable.append([[bool(_placeable(h, o, x[held], r[held], reg))
                               for h in hoops for o in h.orientations]
                              for reg in (None, region)])
        g = group(feet, pieces, hoops, "garment", None)
        out[name] = {
            "hoop_index": c.hoop_index.tolist(), "orientation_deg": c.orientation_deg.tolist(),
            "centre_mm": [[float(v) for v in row] for row in c.centre_mm],
            "piece_index": c.piece_index.tolist(),
            "holds": [np.flatnonzero(row).tolist() for row in c.holds],
            "placeable": placeable,
            "reasons": [hoop_reason(h, hoops, feet, pieces) for h in g.hoopings]}
    (HERE / "golden.json").write_text(json.dumps(out, indent=1) + "\n")


if __name__ == "__main__":
    main()
