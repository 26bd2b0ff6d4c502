"""Rules ``feature-side`` and ``feature-gap``: the stitched triangles and the gaps between them
must be large enough for the machine and thread to form (hoop mm, stretched fabric).

Every interior triangle is a lattice triangle of side a (``resolution_mm``) scaled by its
region's factor s about its centroid: its side is s a. Two lattice triangles sharing an edge
have their centroids 2 r on either side of it, r = a / (2 sqrt 3) the inradius; scaling by s_1
and s_2 moves the two edges (1 - s_1) r and (1 - s_2) r off the shared line, so the gap between
them is (2 - s_1 - s_2) a / (2 sqrt 3): (1 - s) a / sqrt 3 inside one region, the mean of the two
regions' gaps across a core/surround boundary. Triangles meeting only at a vertex are farther
apart ((1 - s) a for the closest of them), so the edge gap is the smallest gap. s = 1 leaves no
gap (solid fill), which is not a violation; nor is a gap under ``NO_GAP_MM`` = 0.05 mm, half the
0.1 mm unit of embroidery files, which the files cannot even represent: such a patch is sewn solid
(its fill differs from 1 by less than about 1 %). Pieces clipped by the outline are not considered
(``patch_design`` already drops those under 0.1 mm^2).
"""
from __future__ import annotations

import math

import numpy as np

from stitchswitch.layout.check.rules.geometry import tessellated
from stitchswitch.layout.check.violation import Violation

SQRT3 = math.sqrt(3.0)
NO_GAP_MM = 0.05


def feature_sizes(geom) -> tuple[float, float | None]:
    """(smallest triangle side, smallest gap or None when there is no gap) in mm."""
    a = geom.resolution_mm
    scales = geom.piece_scale if getattr(geom, "piece_scale", None) is not None else [geom.scale]
    s = np.unique(np.round(np.asarray(scales, dtype=float), 12))
    side = float(s.min()) * a
    gaps = (2.0 - s[:, None] - s[None, :]) * a / (2.0 * SQRT3)
    real = gaps[gaps >= NO_GAP_MM]
    gap = float(real.min()) if real.size else None
    return side, gap


def check(design, limits, eta) -> list[Violation]:
    out = []
    for patch, g in tessellated(design, limits.resolution_mm):   # the others: geometry rule
        side, gap = feature_sizes(g)
        ident = ((patch.id,), (patch.piece,))
        if side < limits.min_side_mm - 1e-9:
            out.append(Violation(
                "feature-side", "error", *ident, side, limits.min_side_mm,
                f"patch {patch.id}: stitched triangles of side {side:.2f} mm (fill "
                f"{patch.fill:g} at resolution {limits.resolution_mm:g} mm) are smaller than "
                f"{limits.min_side_mm:g} mm",
                "raise the fill or tessellate coarser (--resolution)"))
        if gap is not None and gap < limits.min_gap_mm - 1e-9:
            out.append(Violation(
                "feature-gap", "warning", *ident, gap, limits.min_gap_mm,
                f"patch {patch.id}: gaps of {gap:.2f} mm between triangles (fill {patch.fill:g} "
                f"at resolution {limits.resolution_mm:g} mm) are narrower than "
                f"{limits.min_gap_mm:g} mm and may close up",
                "lower the fill, or tessellate coarser (--resolution): both widen the gaps"))
    return out
