"""Rule ``hoop-fit``: every patch fits, at its stretched size plus the hoop margin on each side,
into the design's chosen hoop, or into the machine's largest hoop when none is chosen."""
from __future__ import annotations

from stitchswitch.errors import InvalidInputError
from stitchswitch.layout.check.rules.footprint import hoop_extent_mm
from stitchswitch.layout.check.violation import Violation
from stitchswitch.layout.embroidery.machines import builtin_catalogue

RULE = "hoop-fit"
DEFAULT_MARGIN_MM = 5.0        # when the hoop record carries no margin


def check(design, limits, eta) -> list[Violation]:
    machine = builtin_catalogue().machine(design.machine.name)
    if design.machine.hoop is not None:
        try:
            hoop = machine.hoop(design.machine.hoop)
        except InvalidInputError as exc:
            raise InvalidInputError(f"machine.hoop: {exc}") from None
    else:
        hoop = machine.largest_hoop()
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
