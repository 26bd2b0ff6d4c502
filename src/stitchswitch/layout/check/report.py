"""The whole check of a design as ``stitchswitch check`` reports it: the rules' violations and
the small-pieces warnings, judged at the same limits. The CLI and the demo both report this, so
their JSON says the same things in the same words.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

from stitchswitch.layout.check.constraints import CheckLimits, check_design
from stitchswitch.layout.check.small_pieces import SmallPieces, small_piece_warnings
from stitchswitch.layout.check.violation import Violation

__all__ = ["CheckReport", "check_report"]


@dataclass(frozen=True)
class CheckReport:
    """``violations`` in ``check_design``'s order; ``small_pieces`` in design order."""

    limits: CheckLimits
    violations: tuple[Violation, ...]
    small_pieces: tuple[SmallPieces, ...]

    @property
    def errors(self) -> int:
        return sum(v.severity == "error" for v in self.violations)

    @property
    def warnings(self) -> int:
        return len(self.violations) - self.errors

    @property
    def clean(self) -> bool:
        return not self.violations

    def as_dict(self) -> dict:
        """JSON-ready: a value or limit that is not finite (a rule with no measure) is null."""
        return {"limits": self.limits.as_dict(), "clean": self.clean, "errors": self.errors,
                "warnings": self.warnings,
                "violations": [dict(v.as_dict(), value=_number(v.value), limit=_number(v.limit))
                               for v in self.violations],
                "small_pieces": [w.as_dict() for w in self.small_pieces]}


def _number(v: float):
    return v if math.isfinite(v) else None


def check_report(design, limits: CheckLimits | None = None) -> CheckReport:
    """Every violation of ``design`` against ``limits`` (default: ``CheckLimits()``) and its
    small-pieces warnings."""
    limits = limits or CheckLimits()
    return CheckReport(limits, tuple(check_design(design, limits)),
                       tuple(small_piece_warnings(design, limits)))
