"""One violation of the constraint check: its rule, severity, the patches and pieces involved,
the measured value against the limit (both in mm), and a hint at the fix."""
from __future__ import annotations

from dataclasses import asdict, dataclass

__all__ = ["Violation"]


@dataclass(frozen=True)
class Violation:
    rule: str                      # e.g. "piece-edge", "spacing", "feature-gap"
    severity: str                  # "error" or "warning"
    patches: tuple[str, ...]
    pieces: tuple[str, ...]
    value: float                   # measured, mm
    limit: float                   # the limit it breaks, mm
    message: str
    hint: str = ""                 # what to change to clear it

    def as_dict(self) -> dict:
        d = asdict(self)
        d["patches"], d["pieces"] = list(self.patches), list(self.pieces)
        return d
