"""The model-error budget of ``fem-check``: how far the reduced model may be from the shell.

The paper validates the reduced model against fabricated samples with these errors (Table 1,
validation set): h 24.6 % / 2.23 mm, r_a 15.8 % / 1.82 mm, z_a 31.7 % / 1.45 mm, r_b 16.2 % /
1.80 mm, z_b 25.8 % / 0.99 mm (percentage error / MAE). The reduced model's *model* error (what
its missing physics costs, measured against the shell) is allowed half of that: a keypoint is
within budget when its gap to the shell is at most half the percentage OR at most half the MAE
(the absolute limit keeps nearly flat designs, where a percentage means nothing, judged in mm).
"""
from __future__ import annotations

from dataclasses import dataclass

KEYS = ("h_mm", "r_a_mm", "z_a_mm", "r_b_mm", "z_b_mm")

#: The paper's Table 1, validation set: (percentage error, MAE in mm).
PAPER_VALIDATION = {"h_mm": (24.6, 2.23), "r_a_mm": (15.8, 1.82), "z_a_mm": (31.7, 1.45),
                    "r_b_mm": (16.2, 1.80), "z_b_mm": (25.8, 0.99)}
#: The share of the paper's validation error the model error may take.
SHARE = 0.5


@dataclass(frozen=True)
class Limit:
    """A keypoint's budget: relative (fraction) or absolute (mm), whichever is larger."""

    rel: float
    abs_mm: float

    def allows(self, gap_mm: float, reference_mm: float) -> bool:
        return abs(gap_mm) <= max(self.rel * abs(reference_mm), self.abs_mm)

    def as_dict(self) -> dict:
        return {"rel": self.rel, "abs_mm": self.abs_mm}


BUDGET = {k: Limit(SHARE * pct / 100.0, SHARE * mae) for k, (pct, mae) in PAPER_VALIDATION.items()}
