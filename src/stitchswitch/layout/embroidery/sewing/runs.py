"""Thread runs: the needle records from one tie-in to the next tie-off, with the hygiene rules a
digitizer applies.

A run collects needle points (STITCH, or JUMP for a float the operator clips) and is written
when it ends:

* every point is snapped to the 0.1 mm grid the machine files store, so what is checked here is
  what the machine sews;
* no stitch shorter than ``min_stitch_mm``: a point closer than that to the last kept one is
  dropped (the run's last point is kept, replacing the one before it), and a move that becomes
  longer than ``max_stitch_mm`` is split into equal stitches;
* a jump to the start, a first penetration there, and a *tie-in*: ``lock_stitches`` stitches
  back and forth between the start and the point ``lock_stitch_mm`` along the run (Ink/Stitch's
  "back and forth" lock); where the run is shorter, the lock reaches as far as the piece allows
  (``LOCK_MIN_MM`` is then not guaranteed);
* at the end the same *tie-off* backward along the run, then a TRIM.

The tie records are marked (``StitchPlan.ties``), so the audit can tell them from the fill, and
every record carries the index of the piece it belongs to (``StitchPlan.owners``; -1 in a gap),
so a stitch from one piece to another is known to be a crossing.
"""
from __future__ import annotations

import math

import numpy as np

from stitchswitch.layout.embroidery import planar
from stitchswitch.layout.embroidery.sewing.records import COLOR_CHANGE, END, JUMP, STITCH, TRIM


def snap(p) -> np.ndarray:
    return np.round(np.asarray(p, dtype=float) * 10.0) / 10.0


def _filtered(points: list, min_mm: float, max_mm: float) -> list:
    """The run's (point, command, piece) list without stitches shorter than ``min_mm``."""
    out = [points[0]]
    for p, c, o in points[1:]:
        last = out[-1][0]
        if c == STITCH and planar.length(p - last) < min_mm - 1e-9:
            continue
        out.append((p, c, o))
    end = points[-1]
    if len(points) > 1 and out[-1] is not end:
        # keep where the run ends (the next crossing starts there): drop the point before it
        while len(out) > 1 and planar.length(end[0] - out[-1][0]) < min_mm - 1e-9:
            out.pop()
        if planar.length(end[0] - out[-1][0]) >= min_mm - 1e-9:
            out.append(end)
    split = [out[0]]
    for p, c, o in out[1:]:
        a, oa = split[-1][0], split[-1][2]
        n = max(1, int(math.ceil(planar.length(p - a) / max_mm - 1e-9))) if c == STITCH else 1
        for i in range(1, n):
            split.append((snap(a + (p - a) * i / n), STITCH, o if o == oa else -1))
        split.append((p, c, o))
    return split


def _lock_point(path: list[np.ndarray], room: np.ndarray, length: float) -> np.ndarray:
    """The point at chord distance ``length`` from ``path[0]`` along ``path``; if the path never
    gets that far, the farthest of its points and of the piece's corners pulled 10 % in."""
    s = path[0]
    prev = s
    for q in path[1:]:
        if planar.length(q - s) >= length:
            d = q - prev
            e = prev - s
            a, b, c = planar.dot(d, d), 2 * planar.dot(d, e), planar.dot(e, e) - length * length
            t = (-b + math.sqrt(max(b * b - 4 * a * c, 0.0))) / (2 * a) if a > 0 else 1.0
            return snap(prev + min(max(t, 0.0), 1.0) * d)
        prev = q
    corners = room.mean(axis=0) + 0.9 * (room - room.mean(axis=0))
    cands = [snap(p) for p in list(path[1:]) + list(corners)]
    return max(cands, key=lambda p: (planar.length(p - s), p[0], p[1]))


class Builder:
    """Collects runs and writes them as needle records (see the module docstring)."""

    def __init__(self, prm):
        self.prm = prm
        self.xy: list[np.ndarray] = []
        self.cmd: list[int] = []
        self.tie: list[bool] = []
        self.owner: list[int] = []
        self.run: list | None = None
        self.room_start = self.room_end = None

    def add(self, cmd, p, tie=False, owner=-1):
        self.xy.append(snap(p))
        self.cmd.append(cmd)
        self.tie.append(tie)
        self.owner.append(owner)

    @property
    def running(self) -> bool:
        return self.run is not None

    def extend(self, points, room: np.ndarray, cmd: int = STITCH, owner: int = -1) -> None:
        """Append points to the current run (starting one at the first point if none is open);
        ``room``: the piece they lie in (for a lock that needs more room than the path),
        ``owner``: its index (``StitchPlan.owners``)."""
        pts = [snap(p) for p in points]
        if not pts:
            return
        if self.run is None:
            self.run = [(pts[0], STITCH, owner)]
            self.room_start = np.asarray(room, dtype=float)
            pts = pts[1:]
            cmd_first = STITCH
        else:
            cmd_first = cmd
        for k, p in enumerate(pts):
            self.run.append((p, cmd_first if k == 0 else STITCH, owner))
        self.room_end = np.asarray(room, dtype=float)

    def _lock(self, at: np.ndarray, path: list[np.ndarray], room: np.ndarray, owner: int) -> None:
        a = _lock_point(path, room, self.prm.lock_stitch_mm)
        if planar.length(a - at) < 1e-9:
            return
        for k in range(self.prm.lock_stitches):
            self.add(STITCH, a if k % 2 == 0 else at, tie=True, owner=owner)
        if self.prm.lock_stitches % 2:
            self.add(STITCH, at, tie=True, owner=owner)

    def end_run(self) -> None:
        """Write the open run: jump, tie-in, its stitches, tie-off, trim."""
        if self.run is None:
            return
        prm = self.prm
        pts = _filtered(self.run, prm.min_stitch_mm, prm.max_stitch_mm)
        path = [p for p, _, _ in pts]
        start, first = path[0], pts[0][2]
        self.add(JUMP, start, owner=first)
        self.add(STITCH, start, tie=True, owner=first)       # the first penetration
        self._lock(start, path, self.room_start, first)      # tie-in
        for p, c, o in pts[1:]:
            self.add(c, p, owner=o)
        end, last = path[-1], pts[-1][2]
        self._lock(end, path[::-1], self.room_end, last)     # tie-off
        self.add(TRIM, end, owner=last)
        self.run = None

    def colour_change(self) -> None:
        self.end_run()
        if self.xy:
            self.add(COLOR_CHANGE, self.xy[-1])

    def finish(self, at) -> None:
        self.end_run()
        self.add(END, self.xy[-1] if self.xy else at)
