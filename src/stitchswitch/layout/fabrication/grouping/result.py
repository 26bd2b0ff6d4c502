"""The result of hoop grouping: hoopings (a hoop, its placement and its patches) and a report
on how they were found (MIP or greedy fallback, status, gap, bounds, time)."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from stitchswitch.layout.embroidery.hoop_spec import Hoop
from stitchswitch.layout.embroidery.planar import transform


@dataclass(frozen=True)
class Hooping:
    """One hooping. Hoop coordinates: mm, origin at the centre of the sewing field, x along the
    hoop's width. Garment mode: the field centre sits at ``centre_mm`` on the stretched piece
    ``piece``, the hoop turned by ``orientation_deg`` (0 or 90, counter-clockwise); free mode:
    ``piece`` and ``centre_mm`` are None (the patches go on a separate fabric)."""
    hoop: Hoop
    orientation_deg: int
    patch_ids: tuple[str, ...]
    positions_mm: tuple[tuple[float, float], ...]   # patch centres in hoop coordinates
    piece: str | None = None
    centre_mm: tuple[float, float] | None = None

    def axes(self) -> np.ndarray:
        """Rows: the hoop's x and y axes in piece coordinates."""
        if self.orientation_deg == 90:
            return np.array([[0.0, 1.0], [-1.0, 0.0]])
        return np.eye(2)

    def to_hoop(self, points_mm) -> np.ndarray:
        """Stretched piece coordinates -> hoop coordinates (garment mode)."""
        p = np.asarray(points_mm, dtype=float) - np.asarray(self.centre_mm)
        return transform(p, self.axes().T)

    def to_piece(self, points_mm) -> np.ndarray:
        """Hoop coordinates -> stretched piece coordinates (garment mode)."""
        return transform(points_mm, self.axes()) + np.asarray(self.centre_mm)

    def with_patches(self, patch_ids, positions_mm) -> "Hooping":
        return Hooping(self.hoop, self.orientation_deg, tuple(patch_ids),
                       tuple((float(x), float(y)) for x, y in positions_mm), self.piece,
                       self.centre_mm)


@dataclass(frozen=True)
class SolveReport:
    """How a grouping was found. ``method``: "mip" (HiGHS's answer is used) or
    "greedy-fallback" (the time limit stopped HiGHS before it beat the greedy methods);
    ``status``: HiGHS's status through cvxpy; ``optimal``: proven optimal over the candidates;
    ``mip_gap``: HiGHS's relative gap (None if it has no solution); ``hoopings_lower_bound``: a
    proven lower bound on the number of hoopings (garment mode: from HiGHS's dual bound over
    the candidates; free mode: the geometric bound, see ``free``); ``greedy_hoopings``:
    first-fit-decreasing on the same problem; ``solve_s``: wall time of the whole grouping.
    Garment mode, conflicts avoided (``grouping.conflict_plan``): ``fewest_hoopings`` is the
    set cover's count, ``fewest_hoopings_conflicts`` the frame conflicts that grouping leaves
    in its best order, ``conflicts`` those of the plan used (proven fewest over the candidate
    placements when ``conflicts_exact``); all None otherwise."""
    mode: str
    method: str
    status: str
    optimal: bool
    mip_gap: float | None
    hoopings_lower_bound: int
    greedy_hoopings: int
    candidates: int
    solve_s: float
    time_limit_s: float | None
    note: str = ""
    fewest_hoopings: int | None = None          # garment: the set cover's count (no conflicts
    conflicts: int | None = None                # considered); the plan's frame conflicts;
    conflicts_exact: bool = False               # proven fewest over the candidates;
    fewest_hoopings_conflicts: int | None = None  # conflicts of the fewest-hoopings grouping


@dataclass(frozen=True)
class Grouping:
    mode: str
    hoopings: tuple[Hooping, ...]
    report: SolveReport

    @property
    def count(self) -> int:
        return len(self.hoopings)

    @property
    def hoop_types(self) -> int:
        return len({h.hoop.name for h in self.hoopings})
