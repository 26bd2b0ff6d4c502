"""Rule ``piece-edge``: every patch lies inside its piece, its relaxed footprint at least the
seam allowance plus the edge clearance away from the piece outline."""
from __future__ import annotations

import shapely

from stitchswitch.layout.check.rules.footprint import garment_radius_mm
from stitchswitch.layout.check.violation import Violation

RULE = "piece-edge"


def check(design, limits, eta) -> list[Violation]:
    margin = limits.seam_allowance_mm + limits.edge_clearance_mm
    polys = {}
    for piece in design.pieces:          # make_valid: imported outlines may touch themselves
        poly = shapely.make_valid(shapely.Polygon(piece.outline_mm))
        shapely.prepare(poly)
        polys[piece.name] = poly
    out = []
    for patch in design.patches:
        poly = polys[patch.piece]
        centre = shapely.Point(*patch.centre_mm)
        r = garment_radius_mm(patch, eta)
        to_edge = float(poly.boundary.distance(centre))
        inside = bool(poly.covers(centre))
        clearance = (to_edge if inside else -to_edge) - r
        if clearance >= margin - 1e-9:
            continue
        x, y = patch.centre_mm
        if not inside:
            what = f"its centre ({x:g}, {y:g}) lies outside the piece, {to_edge:.2f} mm from it"
        elif clearance < 0:
            what = (f"its footprint (diameter {2 * r:.2f} mm on the relaxed fabric) crosses the "
                    f"piece outline by {-clearance:.2f} mm")
        else:
            what = f"its footprint is {clearance:.2f} mm from the piece outline"
        out.append(Violation(
            RULE, "error", (patch.id,), (patch.piece,), clearance, margin,
            f"patch {patch.id} on piece {patch.piece}: {what}; keep {margin:g} mm (seam "
            f"allowance {limits.seam_allowance_mm:g} + edge clearance "
            f"{limits.edge_clearance_mm:g})",
            f"move it at least {margin - clearance:.1f} mm away from the outline, onto the piece "
            f"(stitchswitch edit DESIGN {patch.id} --at X,Y), or make it smaller"))
    return out
