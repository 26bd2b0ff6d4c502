"""Built-in garment pieces for the demos, in relaxed garment mm (x right, y up).

These are simplified pattern pieces drawn by stitchswitch (not exported from pattern CAD):
an A-line tennis-skirt front panel and a forearm sleeve panel, sized like a women's M. For a
real pattern, import it: ``stitchswitch import pattern.dxf -o design.json`` (docs/dxf.md).
"""
from __future__ import annotations

import numpy as np

from stitchswitch.layout.garment.design import PieceSpec

SOURCE = "built-in (stitchswitch.demos.garments; simplified, not from pattern CAD)"


def skirt_front_panel() -> PieceSpec:
    """A-line skirt front: waist 360 mm, hem 520 mm (curved by 12 mm), length 400 mm."""
    x = np.linspace(-260.0, 260.0, 27)
    hem = np.column_stack([x, 12.0 * (x / 260.0) ** 2])
    waist_x = np.linspace(180.0, -180.0, 19)
    waist = np.column_stack([waist_x, 400.0 - 8.0 * (waist_x / 180.0) ** 2])
    outline = np.vstack([hem, waist])
    return PieceSpec("skirt-front", "M", SOURCE, outline)


def forearm_sleeve_panel() -> PieceSpec:
    """Forearm sleeve, opened flat: wrist 200 mm, elbow 280 mm, length 280 mm."""
    outline = np.array([[-100.0, 0.0], [100.0, 0.0], [140.0, 280.0], [-140.0, 280.0]])
    return PieceSpec("forearm-sleeve", "M", SOURCE, outline)
