"""Run one inverse-design query for a demo and keep what the summary shows."""
from __future__ import annotations

from dataclasses import asdict

from stitchswitch.demos.demo import InverseStep
from stitchswitch.reduced.design_space.inverse import InverseTarget, inverse_design


def choose(label: str, target: InverseTarget) -> InverseStep:
    """The best confirmed candidate for ``target`` that the check's fabrication rules accept
    (``layout.check.design_point``; inverse_design raises a clear error when the target is not
    achievable under its constraints)."""
    from stitchswitch.layout.check.design_point import for_machine

    result = inverse_design(target, admissible=for_machine())
    if not result.candidates:
        from stitchswitch.errors import InvalidInputError
        raise InvalidInputError(f"{label}: no confirmed design for {target}")
    cands = [c.as_dict() for c in result.candidates]
    return InverseStep(label, asdict(target), cands, cands[0])
