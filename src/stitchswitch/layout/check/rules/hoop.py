"""Rule ``hoop-fit``: every patch fits, at its stretched size (the disc of diameter d, the
footprint fabrication hoops) plus the hoop margin on each side, into the design's chosen hoop,
or into some hoop of its machine when none is chosen (fabrication then picks per hooping).

``design_hoops(design)`` is the set of hoops both this rule and the ``hoopable`` rule consider,
the set ``fabricate`` groups into by default.
"""
from __future__ import annotations

from stitchswitch.layout.check.violation import Violation
from stitchswitch.layout.embroidery.machines import builtin_catalogue

RULE = "hoop-fit"
DEFAULT_MARGIN_MM = 5.0        # when the hoop record carries no margin


def design_hoops(design) -> tuple:
    """The design's ``machine.hoop`` alone, else every hoop of its machine (built-in
    catalogue; the design loader has checked both names)."""
    machine = builtin_catalogue().machine(design.machine.name)
    if design.machine.hoop is not None:
        return (machine.hoop(design.machine.hoop),)
    return tuple(machine.hoops)


def check(design, limits, eta) -> list[Violation]:
    hoops = design_hoops(design)

    def margin(hoop):
        return (limits.hoop_margin_mm if limits.hoop_margin_mm is not None
                else getattr(hoop, "margin_mm", DEFAULT_MARGIN_MM))

    roomiest = max(hoops, key=lambda h: (min(h.width_mm, h.height_mm) - 2 * margin(h),
                                         h.area_mm2))
    side = min(roomiest.width_mm, roomiest.height_mm)
    m = margin(roomiest)
    out = []
    for patch in design.patches:
        need = patch.diameter_mm + 2.0 * m
        if need <= side + 1e-9:
            continue
        chosen = "the design's hoop" if design.machine.hoop is not None else "the roomiest hoop"
        out.append(Violation(
            RULE, "error", (patch.id,), (patch.piece,), need, side,
            f"patch {patch.id}: {patch.diameter_mm:g} mm on the stretched fabric plus a {m:g} mm "
            f"margin on each side needs {need:g} mm; {chosen} {roomiest.name} "
            f"({roomiest.width_mm:g} x {roomiest.height_mm:g} mm) has {side:g} mm",
            f"make the patch at most {side - 2 * m:g} mm across"
            + (" or choose a larger hoop (machine.hoop)" if design.machine.hoop else "")))
    return out
