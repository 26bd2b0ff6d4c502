"""Placing a patch for a target height under the check's rules (paper, section 5: inverse
design connected to placement).

``place_for_height(design, piece, centre_mm, target)``: inverse design
(``reduced.design_space.inverse``) with the rules an unplaced design must meet
(``design_point.for_machine``: feature sizes, hoop fit, in the design's machine and hoop), then
each suggestion, best first, is placed at ``centre_mm`` and checked in the design; the first
that no rule flags is kept. When none passes, the error lists each suggestion's violations and
why inverse design returned no more.
"""
from __future__ import annotations

from stitchswitch.errors import InvalidInputError
from stitchswitch.layout.check.constraints import check_design
from stitchswitch.layout.check.design_point import for_machine
from stitchswitch.layout.garment.placement import place_at

__all__ = ["place_for_height"]


def place_for_height(design, piece: str, centre_mm, target, **place_kwargs):
    """(the design with the patch added, the ``Candidate`` placed)."""
    from stitchswitch.reduced.design_space.cache import map_for
    from stitchswitch.reduced.design_space.inverse import inverse_design

    design.piece(piece)
    material = design.material_object()
    rules = for_machine(design.machine.name, hoop=design.machine.hoop)
    result = inverse_design(target, map_for(material), admissible=rules)
    refused = []
    for cand in result.candidates:
        placed = place_at(design, piece, centre_mm, round(cand.diameter_mm, 3),
                          round(cand.fill, 4), **place_kwargs)
        new_id = placed.patches[-1].id
        found = [v for v in check_design(placed) if new_id in v.patches]
        if not found:
            return placed, cand
        refused.append(f"d = {cand.diameter_mm:.2f} mm, fill {cand.fill:.3f}: "
                       + ", ".join(sorted({v.rule for v in found})))
    why = "; ".join(refused + list(result.dropped)) or "inverse design found no design"
    raise InvalidInputError(f"no design for h = {target.height_mm:g} mm passes the check at "
                            f"({centre_mm[0]:g}, {centre_mm[1]:g}) on {piece}: {why}")
