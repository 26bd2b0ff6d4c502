"""Rule ``model-range``: the patch diameter lies in the reduced model's supported range
(``reduced.model.params.DIAMETER_RANGE_MM``). Outside it the shape cannot be predicted: the
preview, the layout view and the design map refuse the patch, although its stitches could be
written."""
from __future__ import annotations

from stitchswitch.layout.check.violation import Violation
from stitchswitch.reduced.model.params import DIAMETER_RANGE_MM

RULE = "model-range"


def check(design, limits, eta) -> list[Violation]:
    lo, hi = DIAMETER_RANGE_MM
    out = []
    for patch in design.patches:
        d = patch.diameter_mm
        if lo <= d <= hi:
            continue
        limit = lo if d < lo else hi
        out.append(Violation(
            RULE, "error", (patch.id,), (patch.piece,), d, limit,
            f"patch {patch.id}: d = {d:g} mm is outside the model's range [{lo:g}, {hi:g}] mm, "
            "so its shape cannot be predicted",
            f"set a diameter between {lo:g} and {hi:g} mm (stitchswitch edit DESIGN "
            f"{patch.id} --diameter MM)"))
    return out
