"""Rule ``hoop-fit``: every patch fits, at its stretched size plus the hoop margin on each side,
into the design's chosen hoop, or into the machine's largest hoop when none is chosen."""
from __future__ import annotations

from stitchswitch.errors import InvalidInputError
from stitchswitch.layout.check.rules.footprint import hoop_extent_mm
from stitchswitch.layout.check.violation import Violation
from stitchswitch.layout.garment.design_io import machine_hoops

RULE = "hoop-fit"
DEFAULT_MARGIN_MM = 5.0        # when the hoop record carries no margin


def check(design, limits, eta) -> list[Violation]:
    hoops = machine_hoops(design.machine.name)
    if design.machine.hoop is not None:
        match = [h for h in hoops if h.name.lower() == design.machine.hoop.lower()]
        if not match:
            raise InvalidInputError(f"machine.hoop: {design.machine.hoop!r} is not a hoop of the "
                                    f"{design.machine.name}")
        hoop = match[0]
    else:
        hoop = max(hoops, key=lambda h: h.width_mm * h.height_mm)
    margin = (limits.hoop_margin_mm if limits.hoop_margin_mm is not None
              else getattr(hoop, "margin_mm", DEFAULT_MARGIN_MM))
    side = min(hoop.width_mm, hoop.height_mm)
    out = []
    for patch in design.patches:
        need = max(hoop_extent_mm(patch)) + 2.0 * margin
        if need <= side + 1e-9:
            continue
        out.append(Violation(
            RULE, "error", (patch.id,), (patch.piece,), need, side,
            f"patch {patch.id}: {max(hoop_extent_mm(patch)):g} mm on the stretched fabric plus "
            f"a {margin:g} mm margin on each side needs {need:g} mm; the hoop {hoop.name} "
            f"({hoop.width_mm:g} x {hoop.height_mm:g} mm) has {side:g} mm"))
    return out
