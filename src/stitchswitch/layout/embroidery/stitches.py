"""Stitch plans: every piece filled with real fill stitches, joined by one routed thread.

A stitch plan is a list of needle records in hoop coordinates (mm, y up): ``STITCH`` (move and
penetrate), ``JUMP`` (move without penetrating), ``TRIM``, ``COLOR_CHANGE`` and a final ``END``.
Parameters and rules (docs/embroidery.md):

* fills (``fills``): tatami or satin, pull compensation, underlay;
* route (``routing``): the pieces of each thread block in Warnsdorff order from the centre
  outward over the gap graph; every lattice-connected group of a block's pieces (an electrode,
  or all normal pieces of a plain patch) is one thread, bridged through its stitched pieces
  where the walk gets stuck; a trim only between groups;
* travel between neighbouring pieces (``travel``): ``stitch`` (a running stitch straight across
  the gap at its narrowest, the default), ``jump`` (a float the operator clips) or ``trim``
  (tie-off, trim, jump, tie-in; a bridge then becomes a trim too); a move inside the conductive
  block is always a stitch (a trim would cut the conductor);
* hygiene (``runs``): no stitch shorter than ``min_stitch_mm`` outside ties, locks of
  ``lock_stitches`` stitches of ``lock_stitch_mm`` (at least ``LOCK_MIN_MM`` where the piece
  allows) at both ends of every thread run;
* the normal thread first, then a colour change to the conductive thread.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
import shapely

from stitchswitch.errors import InvalidInputError
from stitchswitch.layout.embroidery.machines import default_machine
from stitchswitch.layout.embroidery.planar import length
from stitchswitch.layout.embroidery.sewing import routing
from stitchswitch.layout.embroidery.sewing.fills import fill_piece
from stitchswitch.layout.embroidery.sewing.records import COLOR_CHANGE, END, JUMP, STITCH, TRIM
from stitchswitch.layout.embroidery.sewing.runs import Builder

__all__ = ["STITCH", "JUMP", "TRIM", "COLOR_CHANGE", "END", "StitchParams", "StitchPlan",
           "Thread", "NORMAL_THREAD", "CONDUCTIVE_THREAD", "plan_stitches", "fill_piece"]


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


#: the ways of travelling between neighbouring pieces (``StitchParams.travel``)
TRAVELS = ("stitch", "jump", "trim")
#: a lock stitch is at least this long where the piece allows it (Ink/Stitch's locks: 0.5-1.5 mm)
LOCK_MIN_MM = 0.5
#: pieces smaller than this are sewn, but warned about: a fill of a few needle holes
SMALL_PIECE_AREA_MM2 = 1.0
#: pull compensation is at most this fraction of the gap to the nearest piece (per side)
PULL_COMPENSATION_GAP_FRACTION = 0.25


@dataclass(frozen=True)
class StitchParams:
    row_spacing_mm: float = 0.4
    max_stitch_mm: float = 3.5
    min_stitch_mm: float = 0.3
    satin_max_width_mm: float = 3.5
    underlay: bool = True
    underlay_inset_mm: float = 0.4
    lock_stitch_mm: float = 0.7
    lock_stitches: int = 4
    #: travel between neighbouring pieces: "stitch", "jump" or "trim"
    travel: str = "stitch"
    #: pieces at most this far apart are neighbours (a move between them is a travel)
    travel_run_max_mm: float = 2.5
    #: running-stitch length of travel inside a piece and across a bridge
    run_stitch_mm: float = 2.0
    #: row ends lengthened by this (mm per side) against the knit's pull-in
    pull_compensation_mm: float = 0.1
    stitches_per_minute: float = field(default_factory=_default_speed)
    #: sewing-time allowances (s): a trim (stop, cut, restart), a colour change (rethread or
    #: change the bobbin, by hand)
    trim_s: float = 6.0
    colour_change_s: float = 60.0

    def __post_init__(self):
        if self.travel not in TRAVELS:
            raise InvalidInputError(f"travel {self.travel!r} is not one of " + ", ".join(TRAVELS))
        if not (isinstance(self.lock_stitches, int) and self.lock_stitches >= 3):
            raise InvalidInputError(f"lock_stitches = {self.lock_stitches!r} must be an integer >= 3")
        for name in ("pull_compensation_mm", "trim_s", "colour_change_s"):
            v = getattr(self, name)
            if not (math.isfinite(v) and v >= 0):
                raise InvalidInputError(f"stitch parameter {name} = {v!r} must be >= 0")
        for name in ("row_spacing_mm", "max_stitch_mm", "min_stitch_mm", "satin_max_width_mm",
                     "lock_stitch_mm", "stitches_per_minute", "travel_run_max_mm",
                     "run_stitch_mm"):
            v = getattr(self, name)
            if not (math.isfinite(v) and v > 0):
                raise InvalidInputError(f"stitch parameter {name} = {v!r} must be positive")
        lo, hi = ROW_SPACING_RANGE_MM
        if not lo <= self.row_spacing_mm <= hi:
            raise InvalidInputError(f"stitch parameter row_spacing_mm = {self.row_spacing_mm:g} is "
                                    f"outside [{lo:g}, {hi:g}] mm")
        if self.min_stitch_mm >= self.max_stitch_mm:
            raise InvalidInputError("min_stitch_mm must be smaller than max_stitch_mm")
        if not self.min_stitch_mm <= self.run_stitch_mm <= self.max_stitch_mm:
            raise InvalidInputError(f"run_stitch_mm = {self.run_stitch_mm:g} must lie in "
                                    "[min_stitch_mm, max_stitch_mm]")


@dataclass(frozen=True)
class StitchPlan:
    """Needle records in hoop coordinates (mm, y up) and the threads, in sewing order."""
    xy_mm: np.ndarray          # (n, 2)
    commands: np.ndarray       # (n,) STITCH / JUMP / TRIM / COLOR_CHANGE / END
    threads: tuple[Thread, ...]
    stitches_per_minute: float = field(default_factory=_default_speed)
    #: (n,) bool: the records that belong to a tie-in or tie-off (None: not recorded)
    ties: np.ndarray | None = field(default=None, repr=False, compare=False)
    trim_s: float = 6.0
    colour_change_s: float = 60.0
    #: pieces under ``SMALL_PIECE_AREA_MM2`` that were sewn (warned about)
    small_pieces: int = 0
    #: (n,) int: the piece (``geom.pieces_mm`` index) each record belongs to, -1 over a gap
    #: (None: not recorded)
    owners: np.ndarray | None = field(default=None, repr=False, compare=False)

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
        """Stitches at the machine's speed, plus ``trim_s`` per trim and ``colour_change_s``
        per colour change (docs/embroidery.md)."""
        return (self.stitch_count / self.stitches_per_minute
                + (self.trim_count * self.trim_s + self.color_changes * self.colour_change_s) / 60.0)

    def extents_mm(self) -> tuple[float, float, float, float]:
        """(xmin, ymin, xmax, ymax) over all needle positions except END."""
        p = self.xy_mm[self.commands != END]
        return (float(p[:, 0].min()), float(p[:, 1].min()),
                float(p[:, 0].max()), float(p[:, 1].max()))

    def fabrication_notes(self) -> list[str]:
        notes = [f"thread {i + 1}: {t.name}" for i, t in enumerate(self.threads)]
        if any(t is CONDUCTIVE_THREAD for t in self.threads):
            notes.append(CONDUCTIVE_BOBBIN_NOTE)
        if self.small_pieces:
            notes.append(f"warning: {small_pieces_text(self.small_pieces)}")
        return notes


def small_pieces(geom) -> int:
    """How many of a patch geometry's pieces are under ``SMALL_PIECE_AREA_MM2``: sewn, but a
    fill of a few needle holes that may not hold. The stitch plan, fabrication's sheet and the
    constraint check all count them here."""
    return int(np.count_nonzero(np.asarray(geom.areas_mm2) < SMALL_PIECE_AREA_MM2))


def small_pieces_text(count: int) -> str:
    """The one warning about ``count`` small pieces (``small_pieces``), with what avoids them."""
    return (f"{count} stitched piece(s) under {SMALL_PIECE_AREA_MM2:g} mm^2, a fill of "
            "a few needle holes that may not hold (coarser triangles, --resolution, or a higher "
            "fill avoid them)")


#: where the conductive bobbin goes in and when the normal one comes back
CONDUCTIVE_BOBBIN_NOTE = (
    "conductive block: the paper sews conductive regions with conductive thread in the bobbin "
    "(appendix A, Fig. 13). At the colour change stop, put the conductive bobbin in (and the "
    "conductive thread's top colour); when the conductive block ends, put the normal bobbin "
    "back before the next normal-thread block or the next hooping")




# --- the plan --------------------------------------------------------------------------

def _pull_compensation(polys, prm: StitchParams) -> np.ndarray:
    """Per piece: the pull compensation, at most ``PULL_COMPENSATION_GAP_FRACTION`` of the gap
    to the nearest other piece (so compensated rows never close a hinge)."""
    ext = np.full(len(polys), prm.pull_compensation_mm)
    if len(polys) < 2 or prm.pull_compensation_mm == 0:
        return ext
    tree = shapely.STRtree(polys)
    src, dst = tree.query_nearest(polys, exclusive=True, all_matches=False)
    gap = np.full(len(polys), np.inf)
    gap[src] = shapely.distance(polys[src], polys[dst])
    return np.minimum(ext, PULL_COMPENSATION_GAP_FRACTION * gap)


def _run_inside(a: np.ndarray, b: np.ndarray, step: float) -> list[np.ndarray]:
    """Running stitches from ``a`` to ``b`` (a straight line: inside a convex piece)."""
    n = max(1, int(math.ceil(length(b - a) / step - 1e-9)))
    return [a + (b - a) * i / n for i in range(1, n + 1)]


class _Block:
    """Sews the routed pieces of one thread block into the builder."""

    def __init__(self, b: Builder, prm: StitchParams, pieces, ext, electrode: bool, index):
        self.b, self.prm, self.pieces, self.ext, self.electrode = b, prm, pieces, ext, electrode
        self.index = index                  # block piece -> geometry piece
        self.counts = {"stitch": 0, "jump": 0, "trim": 0, "bridge": 0, "restart": 0}

    def _variant(self, i, entry, exit_):
        options = [fill_piece(self.pieces[i], self.prm, fx, fy, self.ext[i])
                   for fy in (False, True) for fx in (False, True)]
        cost = [(length(v[0] - entry) if entry is not None else 0.0)
                + (length(v[-1] - exit_) if exit_ is not None else 0.0) for v in options]
        return options[int(np.argmin(cost))]

    def _mode(self, step) -> str:
        """restart (a trim), bridge, stitch or jump: electrodes are always stitched; elsewhere
        ``travel`` decides, a bridge becoming a trim or one float under ``trim`` / ``jump``."""
        if step.kind == routing.RESTART:
            return "restart"
        if self.electrode or self.prm.travel == "stitch":
            return "bridge" if step.kind == routing.BRIDGE else "stitch"
        return "restart" if self.prm.travel == "trim" else "jump"

    def sew(self, steps) -> None:
        prm = self.prm
        modes = [self._mode(s) for s in steps]
        connected = [m in ("stitch", "jump", "bridge") for m in modes]
        for m in modes:
            self.counts[m if m != "restart" else "restart"] += 1
        # the crossings: (exit point of the previous piece, entry point of this one) per step,
        # bridges through their stitched pieces
        chains = [None] * len(steps)
        for k in range(1, len(steps)):
            if connected[k]:
                via = steps[k].via if modes[k] == "bridge" else ()
                seq = [steps[k - 1].piece, *via, steps[k].piece]
                chains[k] = [routing.crossing(self.pieces[u], self.pieces[v], prm.min_stitch_mm)
                             for u, v in zip(seq[:-1], seq[1:])]
        for k, step in enumerate(steps):
            i = step.piece
            entry = chains[k][-1][1] if chains[k] else None
            exit_ = chains[k + 1][0][0] if k + 1 < len(steps) and chains[k + 1] else None
            if not connected[k]:
                self.b.end_run()
            path = self._variant(i, entry, exit_)
            if entry is not None:
                self._cross(chains[k], steps[k], modes[k])
                pts = _run_inside(entry, path[0], prm.run_stitch_mm) + list(path)
            else:
                pts = list(path)
            if exit_ is not None:
                pts += _run_inside(path[-1], exit_, prm.run_stitch_mm)
            self.b.extend(pts, self.pieces[i], owner=self.index[i])

    def _cross(self, chain, step, mode) -> None:
        """From the previous piece's exit across the gap(s) to this piece's entry."""
        cmd = JUMP if mode == "jump" else STITCH
        via = step.via if mode == "bridge" else ()
        for h, (_, q) in enumerate(chain):
            into = via[h] if h < len(via) else step.piece
            room = self.pieces[into]
            self.b.extend([q], room, cmd, owner=self.index[into])
            if h + 1 < len(chain):
                self.b.extend(_run_inside(q, chain[h + 1][0], self.prm.run_stitch_mm), room,
                              owner=self.index[into])


def plan_stitches(geom, prm: StitchParams | None = None,
                  center_mm: tuple[float, float] = (0.0, 0.0)) -> StitchPlan:
    """The stitch plan of a patch: normal pieces, colour change, conductive pieces, END; each
    block routed (``routing.route``) and sewn as thread runs (``runs``)."""
    prm = prm or StitchParams()
    offset = np.asarray(center_mm, dtype=float)
    pieces = [np.asarray(p, dtype=float) + offset for p in geom.pieces_mm]
    centroids = np.asarray(geom.centroids_mm, dtype=float) + offset
    polys = np.array([shapely.Polygon(p) for p in pieces] + [None], dtype=object)[:-1]
    ext = _pull_compensation(polys, prm)
    b = Builder(prm)
    threads = []
    conductive = np.asarray(geom.conductive, dtype=bool)
    groups = [(NORMAL_THREAD, ~conductive), (CONDUCTIVE_THREAD, conductive)]
    for thread, mask in groups:
        idx = np.flatnonzero(mask)
        if len(idx) == 0:
            continue
        if threads:
            b.colour_change()
        threads.append(thread)
        electrode = thread is CONDUCTIVE_THREAD
        # every lattice-connected group of the block's pieces is one thread: an electrode must
        # be (and a block planned on its own, as fabrication plans the conductive pieces of a
        # patch, is recognised by its pieces alone), and the normal thread saves its trims
        regions = routing.electrode_regions(centroids[idx], np.ones(len(idx), dtype=bool),
                                            geom.resolution_mm)
        steps = routing.route([pieces[i] for i in idx], centroids[idx], offset,
                              geom.resolution_mm, prm.travel_run_max_mm, regions)
        block = _Block(b, prm, [pieces[i] for i in idx], ext[idx], electrode, idx.tolist())
        block.sew(steps)
    b.finish(offset)
    small = small_pieces(geom)
    return StitchPlan(np.asarray(b.xy, dtype=float).reshape(-1, 2),
                      np.asarray(b.cmd, dtype=np.int8), tuple(threads),
                      prm.stitches_per_minute, np.asarray(b.tie, dtype=bool),
                      prm.trim_s, prm.colour_change_s, small, np.asarray(b.owner, dtype=int))
