"""Stitch generation: every triangle piece filled with real fill stitches.

A stitch plan is a list of needle records in hoop coordinates (mm, y up): ``STITCH`` (move and
penetrate), ``JUMP`` (move without penetrating), ``TRIM``, ``COLOR_CHANGE`` and a final ``END``.
Parameters and rules (docs/embroidery.md):

* tatami fill: horizontal rows ``row_spacing_mm`` apart, sewn back and forth; along a row the
  needle penetrates at most ``max_stitch_mm`` apart on a grid shifted by a third of a stitch from
  row to row (the staggered tatami texture); no stitch shorter than ``min_stitch_mm`` inside a row;
* satin for small pieces: a piece whose width (x extent) is at most ``satin_max_width_mm`` is sewn
  as a zigzag from edge to edge, one stitch per half row spacing;
* optional underlay: a running stitch round the piece inset by ``underlay_inset_mm``;
* tie-in / tie-off: after every jump and before every trim, two lock stitches of
  ``lock_stitch_mm`` (there and back along the first / last stitch);
* travel: to the next piece by one running stitch if it is at most ``travel_run_max_mm`` away,
  otherwise tie-off, trim and jump;
* order: nearest neighbour + 2-opt over the triangle centroids (``ordering``), each thread
  colour separately; the normal thread first, then a colour change to the conductive thread.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from stitchswitch.errors import InvalidInputError
from stitchswitch.layout.embroidery.machines import default_machine
from stitchswitch.layout.embroidery.ordering import visiting_order
from stitchswitch.layout.embroidery.patch_geometry import PatchGeometry

STITCH, JUMP, TRIM, COLOR_CHANGE, END = 0, 1, 2, 3, 4


def _default_speed() -> float:
    """The default machine's top embroidery speed (stitches/min), from the machine catalogue."""
    return default_machine().stitches_per_minute


@dataclass(frozen=True)
class Thread:
    name: str
    rgb: tuple[int, int, int]


NORMAL_THREAD = Thread("embroidery thread", (30, 60, 160))
CONDUCTIVE_THREAD = Thread("conductive thread", (200, 120, 20))


#: Tatami row spacings (mm) that make a fill: finer rows pile needle holes on each other and
#: multiply the stitch count, coarser ones leave the fabric between rows bare.
ROW_SPACING_RANGE_MM = (0.1, 5.0)


@dataclass(frozen=True)
class StitchParams:
    row_spacing_mm: float = 0.4
    max_stitch_mm: float = 3.5
    min_stitch_mm: float = 0.3
    satin_max_width_mm: float = 3.5
    underlay: bool = False
    underlay_inset_mm: float = 0.4
    lock_stitch_mm: float = 0.7
    travel_run_max_mm: float = 2.0
    stitches_per_minute: float = field(default_factory=_default_speed)

    def __post_init__(self):
        for name in ("row_spacing_mm", "max_stitch_mm", "min_stitch_mm", "satin_max_width_mm",
                     "lock_stitch_mm", "stitches_per_minute"):
            v = getattr(self, name)
            if not (math.isfinite(v) and v > 0):
                raise InvalidInputError(f"stitch parameter {name} = {v!r} must be positive")
        lo, hi = ROW_SPACING_RANGE_MM
        if not lo <= self.row_spacing_mm <= hi:
            raise InvalidInputError(f"stitch parameter row_spacing_mm = {self.row_spacing_mm:g} is "
                                    f"outside [{lo:g}, {hi:g}] mm")
        if self.min_stitch_mm >= self.max_stitch_mm:
            raise InvalidInputError("min_stitch_mm must be smaller than max_stitch_mm")


@dataclass(frozen=True)
class StitchPlan:
    """Needle records in hoop coordinates (mm, y up) and the threads, in sewing order."""
    xy_mm: np.ndarray          # (n, 2)
    commands: np.ndarray       # (n,) STITCH / JUMP / TRIM / COLOR_CHANGE / END
    threads: tuple[Thread, ...]
    stitches_per_minute: float = field(default_factory=_default_speed)
    #: (n,) bool: the records that belong to a tie-in or tie-off (None: not recorded)
    ties: np.ndarray | None = field(default=None, repr=False, compare=False)

    @property
    def stitch_count(self) -> int:
        return int(np.count_nonzero(self.commands == STITCH))

    @property
    def trim_count(self) -> int:
        return int(np.count_nonzero(self.commands == TRIM))

    @property
    def jump_count(self) -> int:
        return int(np.count_nonzero(self.commands == JUMP))

    @property
    def color_changes(self) -> int:
        return int(np.count_nonzero(self.commands == COLOR_CHANGE))

    def stitch_lengths_mm(self) -> np.ndarray:
        """Length of every STITCH record's move from the previous needle position."""
        d = np.linalg.norm(np.diff(self.xy_mm, axis=0, prepend=self.xy_mm[:1]), axis=1)
        return d[self.commands == STITCH]

    @property
    def thread_length_mm(self) -> float:
        """Top thread laid on the fabric: the sum of the stitch lengths (no take-up allowance)."""
        return float(self.stitch_lengths_mm().sum())

    @property
    def sewing_time_min(self) -> float:
        """Stitch count / machine speed; trims and the colour change take extra time."""
        return self.stitch_count / self.stitches_per_minute

    def extents_mm(self) -> tuple[float, float, float, float]:
        """(xmin, ymin, xmax, ymax) over all needle positions except END."""
        p = self.xy_mm[self.commands != END]
        return (float(p[:, 0].min()), float(p[:, 1].min()),
                float(p[:, 0].max()), float(p[:, 1].max()))

    def fabrication_notes(self) -> list[str]:
        notes = [f"thread {i + 1}: {t.name}" for i, t in enumerate(self.threads)]
        if any(t is CONDUCTIVE_THREAD for t in self.threads):
            notes.append("at the colour change, thread the conductive thread; the paper sews "
                         "conductive regions with conductive thread in the bobbin (appendix A, "
                         "Fig. 13): wind a conductive bobbin for that block")
        return notes


# --- filling one convex piece --------------------------------------------------------------

def _row_interval(poly: np.ndarray, y: float) -> tuple[float, float] | None:
    xs = []
    for (x0, y0), (x1, y1) in zip(poly, np.roll(poly, -1, axis=0)):
        if (y0 <= y <= y1) or (y1 <= y <= y0):
            if y1 == y0:
                xs += [x0, x1]
            else:
                xs.append(x0 + (y - y0) * (x1 - x0) / (y1 - y0))
    if not xs:
        return None
    return min(xs), max(xs)


def _rows(poly: np.ndarray, spacing: float):
    ymin, ymax = poly[:, 1].min(), poly[:, 1].max()
    n = max(1, int(math.ceil((ymax - ymin) / spacing - 1e-9)))
    out = []
    for k in range(n):
        y = ymin + (ymax - ymin) * (k + 0.5) / n
        iv = _row_interval(poly, y)
        if iv is not None:
            out.append((y, iv[0], iv[1]))
    return out


def _tatami(poly: np.ndarray, prm: StitchParams) -> list[tuple[float, float]]:
    pts = []
    L = prm.max_stitch_mm
    for k, (y, xl, xr) in enumerate(_rows(poly, prm.row_spacing_mm)):
        phase = (k % 3) / 3.0
        m0 = math.ceil((xl + prm.min_stitch_mm) / L - phase)
        grid = [(m + phase) * L for m in range(m0, m0 + int((xr - xl) / L) + 2)]
        inner = [x for x in grid if xl + prm.min_stitch_mm <= x <= xr - prm.min_stitch_mm]
        row = [xl] + inner + [xr]
        # the phase grid is at most L apart; guard the ends against numerical slack
        full = [row[0]]
        for x in row[1:]:
            n = max(1, int(math.ceil((x - full[-1]) / L - 1e-9)))
            full += [full[-1] + (x - full[-1]) * (i + 1) / n for i in range(n)]
        if k % 2:
            full = full[::-1]
        pts += [(x, y) for x in full]
    return pts


def _satin(poly: np.ndarray, prm: StitchParams) -> list[tuple[float, float]]:
    pts = []
    for k, (y, xl, xr) in enumerate(_rows(poly, prm.row_spacing_mm / 2)):
        pts.append((xl, y) if k % 2 == 0 else (xr, y))
    return pts


def _underlay(poly: np.ndarray, prm: StitchParams) -> list[tuple[float, float]]:
    c = poly.mean(axis=0)
    e = np.roll(poly, -1, axis=0) - poly
    n = np.column_stack([e[:, 1], -e[:, 0]]) / np.linalg.norm(e, axis=1)[:, None]
    inradius = float(np.min(np.abs(np.einsum("ij,ij->i", c - poly, n))))
    f = 1.0 - prm.underlay_inset_mm / inradius
    if f <= 0.2:
        return []
    ring = c + f * (poly - c)
    pts = []
    for a, b in zip(ring, np.roll(ring, -1, axis=0)):
        n_seg = max(1, int(math.ceil(np.linalg.norm(b - a) / prm.max_stitch_mm)))
        pts += [tuple(a + (b - a) * i / n_seg) for i in range(n_seg)]
    pts.append(tuple(ring[0]))
    return pts


def fill_piece(poly: np.ndarray, prm: StitchParams, flip_x: bool = False,
               flip_y: bool = False) -> np.ndarray:
    """Needle penetrations filling one convex piece; the flips choose the starting corner."""
    p = np.asarray(poly, dtype=float).copy()
    sx, sy = (-1.0 if flip_x else 1.0), (-1.0 if flip_y else 1.0)
    q = p * [sx, sy]
    if sx * sy < 0:
        q = q[::-1]                     # keep counter-clockwise after a reflection
    width = q[:, 0].max() - q[:, 0].min()
    body = _satin(q, prm) if width <= prm.satin_max_width_mm else _tatami(q, prm)
    if not body:
        body = [tuple(q.mean(axis=0))]
    pts = body
    if prm.underlay and width > prm.satin_max_width_mm:
        ul = _underlay(q, prm)
        if ul:
            start = np.asarray(body[0])
            k = int(np.argmin(np.linalg.norm(np.asarray(ul[:-1]) - start, axis=1)))
            ring = ul[:-1]
            pts = ring[k:] + ring[:k] + [ring[k]] + body
    return np.asarray(pts) * [sx, sy]


# --- the plan --------------------------------------------------------------------------

class _Builder:
    def __init__(self, prm: StitchParams):
        self.prm = prm
        self.xy: list[tuple[float, float]] = []
        self.cmd: list[int] = []
        self.tie: list[bool] = []
        self.trimmed = True

    @property
    def needle(self):
        return np.asarray(self.xy[-1]) if self.xy else None

    def add(self, cmd, p, tie=False):
        self.xy.append((float(p[0]), float(p[1])))
        self.cmd.append(cmd)
        self.tie.append(tie)

    def _lock(self, at, toward):
        d = np.asarray(toward) - np.asarray(at)
        n = np.linalg.norm(d)
        if n < 1e-9:
            return
        step = d / n * min(self.prm.lock_stitch_mm, n)
        self.add(STITCH, np.asarray(at) + step, tie=True)
        self.add(STITCH, at, tie=True)

    def tie_off_and_trim(self):
        if self.trimmed:
            return
        k = len(self.xy) - 1
        while k > 0 and np.allclose(self.xy[k - 1], self.xy[-1]):
            k -= 1
        if k > 0:
            self._lock(self.xy[-1], self.xy[k - 1])
        self.add(TRIM, self.xy[-1])
        self.trimmed = True

    def sew(self, path: np.ndarray):
        start = path[0]
        needle = self.needle
        if (not self.trimmed and needle is not None
                and np.linalg.norm(start - needle) <= self.prm.travel_run_max_mm):
            self.add(STITCH, start)              # travel as one running stitch
        else:
            self.tie_off_and_trim()
            if needle is None or np.linalg.norm(start - needle) > 0:
                self.add(JUMP, start)
            self.add(STITCH, start, tie=True)    # first penetration
            nxt = next((q for q in path[1:] if np.linalg.norm(q - start) > 1e-9), None)
            if nxt is not None:
                self._lock(start, nxt)           # tie-in
            self.trimmed = False
        for q in path[1:]:
            self.add(STITCH, q)


def plan_stitches(geom: PatchGeometry, prm: StitchParams | None = None,
                  center_mm: tuple[float, float] = (0.0, 0.0)) -> StitchPlan:
    """The stitch plan of a patch: normal pieces, colour change, conductive pieces, END."""
    prm = prm or StitchParams()
    b = _Builder(prm)
    threads = []
    groups = [(NORMAL_THREAD, ~geom.conductive), (CONDUCTIVE_THREAD, geom.conductive)]
    offset = np.asarray(center_mm, dtype=float)
    for thread, mask in groups:
        idx = np.flatnonzero(mask)
        if len(idx) == 0:
            continue
        if threads:
            b.tie_off_and_trim()
            b.add(COLOR_CHANGE, b.xy[-1])
        threads.append(thread)
        order = idx[visiting_order(geom.centroids_mm[idx])]
        for i in order:
            poly = geom.pieces_mm[i] + offset
            variants = [fill_piece(poly, prm, fx, fy) for fy in (False, True)
                        for fx in (False, True)]
            needle = b.needle
            if needle is None:
                path = variants[0]
            else:
                dist = [np.linalg.norm(v[0] - needle) for v in variants]
                path = variants[int(np.argmin(dist))]
            b.sew(path)
    b.tie_off_and_trim()
    b.add(END, b.xy[-1] if b.xy else offset)
    return StitchPlan(np.asarray(b.xy, dtype=float), np.asarray(b.cmd, dtype=np.int8),
                      tuple(threads), prm.stitches_per_minute, np.asarray(b.tie, dtype=bool))
