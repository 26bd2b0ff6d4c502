"""Rule ``spacing``: patches on the same piece keep ``min_spacing_mm`` of bare relaxed fabric
between their footprints (edge to edge; a negative spacing is an overlap)."""
from __future__ import annotations

import numpy as np

from stitchswitch.layout.check.rules.footprint import garment_radius_mm
from stitchswitch.layout.check.violation import Violation

RULE = "spacing"


def check(design, limits, eta) -> list[Violation]:
    out = []
    by_piece: dict[str, list] = {}
    for patch in design.patches:
        by_piece.setdefault(patch.piece, []).append(patch)
    for piece in design.pieces:
        patches = by_piece.get(piece.name, [])
        if len(patches) < 2:
            continue
        c = np.array([p.centre_mm for p in patches])
        r = np.array([garment_radius_mm(p, eta) for p in patches])
        dist = np.hypot(*(c[:, None, :] - c[None, :, :]).transpose(2, 0, 1))
        gap = dist - r[:, None] - r[None, :]
        i, j = np.nonzero(np.triu(gap < limits.min_spacing_mm - 1e-9, k=1))
        for a, b in zip(i.tolist(), j.tolist()):
            g = float(gap[a, b])
            what = f"overlap by {-g:.2f} mm" if g < 0 else f"are {g:.2f} mm apart edge to edge"
            out.append(Violation(
                RULE, "error", (patches[a].id, patches[b].id), (piece.name,), g,
                limits.min_spacing_mm,
                f"patches {patches[a].id} and {patches[b].id} on piece {piece.name} {what} "
                f"(relaxed fabric); keep {limits.min_spacing_mm:g} mm",
                f"move one of them {limits.min_spacing_mm - g:.1f} mm farther from the other "
                f"(stitchswitch edit DESIGN {patches[b].id} --at X,Y)"))
    return out
