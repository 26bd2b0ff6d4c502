"""Stitching order: hoopings so that no frame clamps an already stitched patch, where avoidable.

Garment mode. When hooping a is set up, its frame ring (``frame_width_mm`` around the field)
presses every patch it touches; that is harmless unless the patch is already stitched. Let
W[a, b] be the number of patches of hooping b touched by a's frame ring (same piece). An order
costs the sum of W[a, b] over the pairs where b comes before a; each such (a, patch) pair is a
*conflict*. Hooping b should therefore come after every a whose frame touches it: a cycle of
such relations makes some conflict unavoidable.

* up to ``EXACT_MAX`` hoopings: exact minimum by dynamic programming over subsets (the cost of
  putting a next depends only on the set already placed); among the minimal orders the
  lexicographically first (hoopings numbered in their grouping order) is taken, so the result
  is deterministic and the reported conflicts are unavoidable for this grouping;
* more: greedy, each step the hooping with the fewest new conflicts, ties to the one whose own
  patches fewer remaining frames touch, then the lowest number, or the order given when that
  has fewer conflicts (a plan of ``grouping.conflict_plan`` comes ordered); the conflicts are
  then minimal only heuristically (``exact`` is False).

Within a hooping the patches are sewn in a short travel order: nearest neighbour from the
lowest-left patch, improved by 2-opt (``ordering.visiting_order``). Free mode has no conflicts
(every hooping is its own piece of fabric); only the patch order is set.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from stitchswitch.layout.check.rules.hoopable import ring_touches
from stitchswitch.layout.embroidery.ordering import visiting_order
from stitchswitch.layout.fabrication.grouping.result import Hooping

EXACT_MAX = 14


@dataclass(frozen=True)
class Conflict:
    """The frame of the hooping at ``hooping`` (0-based position in the stitching order)
    lands on ``patch``, stitched earlier in the hooping at ``stitched_in``."""
    hooping: int
    patch: str
    stitched_in: int


@dataclass(frozen=True)
class StitchingOrder:
    hoopings: tuple[Hooping, ...]     # in stitching order, patches in sewing order
    conflicts: tuple[Conflict, ...]
    exact: bool                       # True: the conflicts are the unavoidable minimum


def frame_contacts(hoopings, feet) -> list[list[list[str]]]:
    """contacts[a][b]: ids of the patches of hooping b that hooping a's frame ring touches."""
    by_id = {f.id: f for f in feet}
    k = len(hoopings)
    out = [[[] for _ in range(k)] for _ in range(k)]
    for a, ha in enumerate(hoopings):
        if ha.piece is None:
            continue
        fw, fh = ha.hoop.field_mm(ha.orientation_deg)
        for b, hb in enumerate(hoopings):
            if a == b or hb.piece != ha.piece:
                continue
            fs = [by_id[i] for i in hb.patch_ids]
            x = np.array([f.centre_mm[0] for f in fs])
            y = np.array([f.centre_mm[1] for f in fs])
            r = np.array([f.radius_mm for f in fs])
            hit = ring_touches(np.array([ha.centre_mm[0]]), np.array([ha.centre_mm[1]]), fw, fh,
                               ha.hoop.frame_width_mm, x, y, r)[0]
            out[a][b] = [f.id for f, t in zip(fs, hit) if t]
    return out


def _exact(w: np.ndarray) -> list[int]:
    k = len(w)
    full = (1 << k) - 1
    # cost[v][S] = sum of w[v, b] over b in S, built bit by bit
    masks = np.arange(1 << k)
    cost = np.zeros((k, 1 << k), dtype=np.int64)
    for b in range(k):
        cost += np.where((masks >> b) & 1, w[:, b][:, None], 0)
    best = np.full(1 << k, np.iinfo(np.int64).max // 4, dtype=np.int64)
    best[full] = 0
    for s in range(full - 1, -1, -1):           # best[s]: least cost to finish after s
        free = [v for v in range(k) if not (s >> v) & 1]
        best[s] = min(cost[v, s] + best[s | (1 << v)] for v in free)
    order, s = [], 0
    while s != full:
        v = next(v for v in range(k) if not (s >> v) & 1
                 and cost[v, s] + best[s | (1 << v)] == best[s])
        order.append(v)
        s |= 1 << v
    return order


def _greedy(w: np.ndarray) -> list[int]:
    k = len(w)
    left, order = list(range(k)), []
    while left:
        def score(v):
            new = sum(w[v, b] for b in order)
            later = sum(w[a, v] for a in left if a != v)
            return (new, later, v)
        v = min(left, key=score)
        order.append(v)
        left.remove(v)
    return order


def _cost(w: np.ndarray, order) -> int:
    """Conflicts of ``order``: w[a, b] over the pairs with b before a."""
    return int(sum(w[a, b] for p, a in enumerate(order) for b in order[:p]))


def _sew_order(h: Hooping) -> Hooping:
    if len(h.patch_ids) < 2:
        return h
    idx = visiting_order(np.asarray(h.positions_mm, dtype=float))
    return h.with_patches([h.patch_ids[i] for i in idx], [h.positions_mm[i] for i in idx])


def order_hoopings(hoopings, feet) -> StitchingOrder:
    """The stitching order of ``hoopings`` (see the module docstring)."""
    hoopings = tuple(hoopings)
    contacts = frame_contacts(hoopings, feet)
    w = np.array([[len(c) for c in row] for row in contacts], dtype=np.int64).reshape(
        len(hoopings), len(hoopings))
    exact = len(hoopings) <= EXACT_MAX
    order = (_exact(w) if exact else _greedy(w)) if w.any() else list(range(len(hoopings)))
    if not exact and _cost(w, list(range(len(hoopings)))) < _cost(w, order):
        order = list(range(len(hoopings)))       # the order given (a planned one) is better
    pos = {v: p for p, v in enumerate(order)}
    conflicts = []
    for p, a in enumerate(order):
        for b in order[:p]:
            for pid in contacts[a][b]:
                conflicts.append(Conflict(p, pid, pos[b]))
    return StitchingOrder(tuple(_sew_order(hoopings[v]) for v in order), tuple(conflicts), exact)
