"""Hoop grouping, both modes behind one call (docs/fabrication.md).

``group(feet, pieces, hoops, mode)``: ``"garment"`` keeps every patch where it is on its piece
and chooses hoop placements (``garment``); ``"free"`` packs the patches into hoops of
separate fabric (``free``). Both state a set cover in cvxpy, solve it with HiGHS, report
the gap and the time, and fall back to a greedy method when a time limit stops HiGHS first;
garment mode then plans hoopings and order together for the fewest frame conflicts
(``conflict_plan``).
"""
from __future__ import annotations

from stitchswitch.errors import InvalidInputError
from stitchswitch.layout.fabrication.grouping.free import group_free
from stitchswitch.layout.fabrication.grouping.garment import group_garment
from stitchswitch.layout.fabrication.grouping.result import Grouping

MODES = ("garment", "free")


def group(feet, pieces, hoops, mode: str = "garment", time_limit_s: float | None = None,
          spacing_mm: float = 10.0, avoid_conflicts: bool = True) -> Grouping:
    """The hoopings of ``feet``; garment mode chooses them and their order for the fewest
    frame conflicts first unless ``avoid_conflicts`` is False (then: fewest hoopings)."""
    if mode not in MODES:
        raise InvalidInputError(f"unknown mode {mode!r}; the modes are " + ", ".join(MODES))
    if time_limit_s is not None and not time_limit_s > 0:
        raise InvalidInputError(f"time limit {time_limit_s!r} s must be positive")
    if not hoops:
        raise InvalidInputError("no hoops to group the patches into")
    import cvxpy  # noqa: F401  - loaded here (about 1 s the first time), not in the timed solve
    if mode == "garment":
        return group_garment(feet, pieces, hoops, time_limit_s, avoid_conflicts)
    return group_free(feet, hoops, spacing_mm, time_limit_s)
