"""Patch footprints: the extent of a patch on the hoop (stretched mm) and on the garment."""
from __future__ import annotations

import numpy as np


def hoop_extent_mm(patch) -> tuple[float, float]:
    """(width, height) the patch's stitches occupy on the hoop: the outline's bounding box, or
    the circle's diameter."""
    if patch.outline_mm is not None:
        w, h = np.ptp(patch.outline_mm, axis=0)
        return float(w), float(h)
    return patch.diameter_mm, patch.diameter_mm


def garment_radius_mm(patch, eta: float) -> float:
    """Radius of the circle about the centre holding the flat relaxed footprint: d / (2 eta),
    or the outline's farthest point / eta (never more than d / (2 eta))."""
    if patch.outline_mm is not None:
        return float(np.hypot(patch.outline_mm[:, 0], patch.outline_mm[:, 1]).max()) / eta
    return patch.diameter_mm / (2.0 * eta)
