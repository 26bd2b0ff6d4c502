"""The hoop-placement cases of tests/test_hoop_box.py and of its golden file
(tests/data/hoop_box/make_golden.py): the two demo designs and random patches on a rectangle
and on the stretched skirt panel, each as (footprints, stretched pieces, hoops)."""
from __future__ import annotations

import numpy as np

from stitchswitch.layout.embroidery.machines import default_machine
from stitchswitch.layout.fabrication.fabricate import grouping_hoops
from stitchswitch.layout.fabrication.grouping.footprints import Footprint, StretchedPiece, stretch
from stitchswitch.layout.garment.design_io import load_design

DEMOS = ("tennis-pocket", "forearm-interface")


def _random_rows(n, seed, outline, edge_mm, dmin=15.0, dmax=60.0, gap=6.0):
    import shapely
    poly = shapely.Polygon(outline).buffer(-edge_mm)
    x0, y0, x1, y1 = poly.bounds
    rng = np.random.default_rng(seed)
    rows = []
    while len(rows) < n:
        d = rng.uniform(dmin, dmax)
        x, y = rng.uniform(x0, x1), rng.uniform(y0, y1)
        if not poly.contains(shapely.Point(x, y).buffer(d / 2)):
            continue
        if all(np.hypot(x - a, y - b) >= (d + c) / 2 + gap for a, b, c in rows):
            rows.append((x, y, d))
    return rows


def cases(data_dir) -> dict:
    """name -> (feet, pieces, hoops)."""
    out = {}
    for name in DEMOS:
        design = load_design(data_dir / f"{name}.json")
        feet, pieces = stretch(design, float(design.material_object().eta))
        out[name] = (feet, pieces, grouping_hoops(design))
    hoops = default_machine().hoops
    rect = np.array([[0, 0], [600, 0], [600, 500], [0, 500]], dtype=float)
    skirt = load_design(data_dir / "tennis-pocket.json").pieces[0]
    skirt_mm = np.asarray(skirt.outline_mm) * 1.7
    shapes = {"rect": (rect, 0.0, 50.0), "skirt": (skirt_mm, 0.0, 50.0),
              "skirt-blank": (skirt_mm, 40.0, 5.0)}       # (outline, blank, edge distance)
    for shape, (outline, blank, edge) in shapes.items():
        for seed in range(2):
            rows = _random_rows(10, seed, outline, edge)
            feet = tuple(Footprint(f"p{i}", shape, (float(x), float(y)), float(d))
                         for i, (x, y, d) in enumerate(rows))
            out[f"{shape}-{seed}"] = (feet, (StretchedPiece(shape, outline, blank),), hoops)
    return out
