"""What a stitch plan does to the patch, measured as an embroiderer and the mechanism see it.

* **gap crossings**: thread laid over unstitched fabric. A thread segment is a move to a STITCH
  record, or a JUMP while the thread is still attached (no TRIM or colour change since the last
  penetration: the float lies on the fabric until someone clips it). It is a *crossing* when
  its two ends belong to different pieces (it joins two islands) and more than
  ``tolerance_mm`` of it lies outside the stitched pieces (0.1 mm: gaps narrower than that, at
  fills near 1, are not counted); its crossing length is that part. Which piece a needle
  position belongs to is the plan's record (``StitchPlan.owners``) where it has one; otherwise
  the piece that contains it (within 1e-6 mm; the plan is then taken unrounded, its points lie
  exactly on or in their pieces).
* **short stitches**: STITCH moves shorter than ``min_stitch_mm`` outside ties (a zero-length
  stitch, a second penetration in the same hole, counts).
* **ties**: each maximal run of records the plan marks as tie (``StitchPlan.ties``); its
  stitches are the STITCH records of non-zero length in it.
* **electrodes**: each conductive region (conductive pieces joined when their lattice triangles
  share a vertex, centroids at most 1.2 sides apart) and the connected components of the
  conductive thread's stitch graph that touch it (nodes: needle positions, equal within 0.05 mm;
  edges: thread segments). An electrode is one continuous conductor when that count is 1.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import shapely
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components

from stitchswitch.layout.embroidery.sewing import records as st
from stitchswitch.layout.embroidery.sewing.routing import electrode_regions

#: needle positions closer than this are one hole (the files store 0.1 mm)
_SAME_HOLE_MM = 0.05


@dataclass(frozen=True)
class ThreadAudit:
    gap_crossings: int                 # thread segments over unstitched fabric
    gap_crossing_mm: float             # their total length outside the stitched pieces
    trims: int
    short_stitches: int                # stitches < min_stitch_mm outside ties
    ties: int
    min_tie_stitches: int              # fewest stitches in one tie (0 without ties)
    min_tie_stitch_mm: float           # shortest non-zero tie stitch (0 without ties)
    electrode_components: tuple[int, ...]   # per conductive region: stitch-graph components

    @property
    def electrodes_connected(self) -> bool:
        return all(c == 1 for c in self.electrode_components)

    def as_dict(self) -> dict:
        return {"gap_crossings": self.gap_crossings,
                "gap_crossing_mm": round(self.gap_crossing_mm, 3), "trims": self.trims,
                "short_stitches": self.short_stitches, "ties": self.ties,
                "min_tie_stitches": self.min_tie_stitches,
                "min_tie_stitch_mm": round(self.min_tie_stitch_mm, 3),
                "electrode_components": list(self.electrode_components)}


def thread_segments(plan, rounded: bool = True):
    """(a, b, thread, k): start and end (m, 2) of every thread segment, its thread index and
    the record it ends at."""
    xy, cmd = plan.xy_mm, plan.commands
    if rounded:
        xy = np.round(xy * 10.0) / 10.0
    a, b, thread, at = [], [], [], []
    attached, colour = False, 0
    for k in range(len(cmd)):
        c = cmd[k]
        if c in (st.TRIM, st.COLOR_CHANGE, st.END):
            attached = False
            colour += c == st.COLOR_CHANGE
            continue
        if attached and k > 0:
            a.append(xy[k - 1])
            b.append(xy[k])
            thread.append(colour)
            at.append(k)
        if c == st.STITCH:
            attached = True
    if not a:
        return np.zeros((0, 2)), np.zeros((0, 2)), np.zeros(0, dtype=int), np.zeros(0, dtype=int)
    return np.asarray(a), np.asarray(b), np.asarray(thread), np.asarray(at)


def _owners(plan, pieces) -> np.ndarray:
    """The piece each record belongs to: the plan's record, else the containing piece."""
    if getattr(plan, "owners", None) is not None:
        return np.asarray(plan.owners)
    polys = [shapely.Polygon(p).buffer(1e-6) for p in pieces]
    tree = shapely.STRtree(polys)
    pts, idx = tree.query(shapely.points(plan.xy_mm), predicate="within")
    owner = np.full(len(plan.xy_mm), -1)
    owner[pts[::-1]] = idx[::-1]                   # the lowest index where pieces touch
    return owner


def _outside_mm(a, b, area) -> np.ndarray:
    """Length of each segment a-b outside the (prepared) ``area``."""
    out = np.zeros(len(a))
    moving = np.flatnonzero(np.linalg.norm(b - a, axis=1) > 0)
    if len(moving) == 0:
        return out
    lines = shapely.linestrings(np.stack([a[moving], b[moving]], axis=1))
    leaves = ~shapely.covered_by(lines, area)          # the fast test first
    out[moving[leaves]] = shapely.length(shapely.difference(lines[leaves], area))
    return out


def _short_and_ties(plan, min_stitch_mm: float):
    xy = np.round(plan.xy_mm * 10.0) / 10.0
    step = np.linalg.norm(np.diff(xy, axis=0, prepend=xy[:1]), axis=1)
    stitch = plan.commands == st.STITCH
    tie = plan.ties if plan.ties is not None else np.zeros(len(stitch), dtype=bool)
    short = int(np.count_nonzero(stitch & ~tie & (step < min_stitch_mm - 1e-9)))
    counts, lengths = [], []
    k, n = 0, len(tie)
    while k < n:
        if not tie[k]:
            k += 1
            continue
        j = k
        while j < n and tie[j]:
            j += 1
        run = np.arange(k, j)
        moved = run[stitch[run] & (step[run] > 0)]
        counts.append(len(moved))
        lengths += list(step[moved])
        k = j
    return short, counts, lengths


def _electrode_components(plan, a, b, thread, pieces, regions, tolerance_mm) -> tuple[int, ...]:
    conductive = [k for k, t in enumerate(plan.threads) if t.name.startswith("conductive")]
    if not regions:
        return ()
    keep = np.isin(thread, conductive)
    a, b = a[keep], b[keep]
    if len(a) == 0:
        return tuple(0 for _ in regions)
    pts = np.vstack([a, b])
    keys = np.round(pts / _SAME_HOLE_MM).astype(np.int64)
    _, node = np.unique(keys, axis=0, return_inverse=True)
    node = node.ravel()
    m = len(a)
    n_nodes = int(node.max()) + 1
    graph = coo_matrix((np.ones(m), (node[:m], node[m:])), shape=(n_nodes, n_nodes))
    _, label = connected_components(graph, directed=False)
    where = np.zeros((n_nodes, 2))
    where[node] = pts
    out = []
    for region in regions:
        area = shapely.union_all([shapely.Polygon(pieces[i]) for i in region]).buffer(tolerance_mm)
        inside = shapely.contains_xy(area, where[:, 0], where[:, 1])
        out.append(len(np.unique(label[inside])))
    return tuple(out)


def audit(plan, pieces_mm, conductive: np.ndarray, centroids_mm: np.ndarray,
          resolution_mm: float, min_stitch_mm: float = 0.3,
          tolerance_mm: float = 0.1) -> ThreadAudit:
    """The audit of ``plan`` sewn over ``pieces_mm`` (hoop coordinates, as in the plan)."""
    pieces = [np.asarray(p, dtype=float) for p in pieces_mm]
    stitched = shapely.union_all([shapely.Polygon(p) for p in pieces])
    shapely.prepare(stitched)
    a, b, thread, at = thread_segments(plan)
    owner = _owners(plan, pieces)
    joins = np.flatnonzero(owner[at - 1] != owner[at]) if len(at) else np.zeros(0, dtype=int)
    ua, ub, _, _ = thread_segments(plan, rounded=getattr(plan, "owners", None) is not None)
    outside = np.zeros(len(a))
    outside[joins] = _outside_mm(ua[joins], ub[joins], stitched)
    crossing = outside > tolerance_mm
    short, tie_counts, tie_lengths = _short_and_ties(plan, min_stitch_mm)
    regions = electrode_regions(np.asarray(centroids_mm, dtype=float),
                                np.asarray(conductive, dtype=bool), resolution_mm)
    comps = _electrode_components(plan, a, b, thread, pieces, regions, 0.2)
    return ThreadAudit(int(crossing.sum()), float(outside[crossing].sum()), plan.trim_count, short,
                       len(tie_counts), min(tie_counts, default=0),
                       float(min(tie_lengths, default=0.0)), comps)
