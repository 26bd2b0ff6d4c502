"""Run one inverse-design query for a demo and keep what the summary shows."""
from __future__ import annotations

from dataclasses import asdict

from stitchswitch.demos.demo import InverseStep
from stitchswitch.reduced.design_space.inverse import InverseTarget, inverse_design


def choose(label: str, target: InverseTarget) -> InverseStep:
    """The best confirmed candidate for ``target`` (inverse_design raises a clear error when the
    target is not achievable under its constraints)."""
    result = inverse_design(target)
    if not result.candidates:
        from stitchswitch.errors import InvalidInputError
        raise InvalidInputError(f"{label}: no confirmed design for {target}")
    cands = [c.as_dict() for c in result.candidates]
    return InverseStep(label, asdict(target), cands, cands[0])
