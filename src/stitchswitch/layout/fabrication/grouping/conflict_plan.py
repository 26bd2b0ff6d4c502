"""Hoopings and their order chosen together, so that no hoop frame lands on a stitched patch.

A frame conflict is a hooping whose frame ring touches a patch stitched in an earlier hooping
(``layout.fabrication.order``): the frame crushes the dome or marks the fabric. Grouping for the
fewest hoopings first and ordering afterwards leaves many (17 to 23 on the benchmark's 60-patch
layouts), because the grouping cannot see the order. Here a plan is a sequence of candidate
placements (``candidates``), each stitching the patches it holds that are not stitched yet, and
its cost is lexicographic: **frame conflicts first** (one conflict costs more than any number
of extra hoopings saves), then hoopings, then smaller hoops.

The search runs backwards in time. With R the patches still to be stitched *before* the part
of the plan already fixed, putting placement c just before that part costs |T_c & R| conflicts
(T_c: the patches c's frame ring touches; every patch of R except those c stitches is stitched
before c, and c never touches a patch it holds) and leaves R minus the patches c holds. Taking
all of them is never worse: the cost of finishing is monotone in R. So the state is R alone,
and a move is a placement holding some patch of R:

* up to ``EXACT_MAX`` patches per piece: Dijkstra over all 2^n states, integer costs
  (conflicts, then hoopings, then hoop rank): the plan is optimal over the candidate
  placements (``exact``), so it has no conflict whenever a conflict-free plan over the
  candidates exists;
* more: a beam search, layer by layer (one hooping per layer), keeping the ``BEAM`` best states
  by conflicts + alpha x patches left (one search for each alpha of ``ALPHAS``: a state with
  few conflicts but many patches left tends to collect them later), states that cannot beat
  the best finished plan dropped; not proven optimal. The caller also plans the
  fewest-hoopings grouping's own placements exactly (at most 2^k states for k placements) and
  keeps the better plan.

Pieces are independent (a frame presses only fabric of its own piece), so each piece is
planned alone. Masks are packed 64-bit words (``bitsets``), so any number of patches works.
"""
from __future__ import annotations

import heapq
from dataclasses import dataclass

import numpy as np

from stitchswitch.layout.fabrication.grouping import bitsets

__all__ = ["EXACT_MAX", "BEAM", "Plan", "plan_piece", "plan_cost"]

#: the largest piece (patches) planned exactly (2^n states)
EXACT_MAX = 12
#: states kept per layer by the beam search
BEAM = 48
#: the beam search's weights of a patch left against a conflict, one search each
ALPHAS = (0.0, 0.25, 0.5, 1.0, 2.0)


@dataclass(frozen=True)
class Plan:
    """Candidate indices in stitching order, each with the patch indices it stitches."""
    steps: tuple[tuple[int, tuple[int, ...]], ...]
    conflicts: int
    exact: bool


def _popcount(words: np.ndarray) -> np.ndarray:
    return np.bitwise_count(words).sum(axis=-1, dtype=np.int64)


def plan_cost(steps, touches: np.ndarray) -> int:
    """Frame conflicts of a plan: per step, the patches its frame touches that earlier steps
    stitched. ``touches``: (m, n) bool."""
    done = np.zeros(touches.shape[1], dtype=bool)
    total = 0
    for c, members in steps:
        total += int((touches[c] & done).sum())
        done[list(members)] = True
    return total


def _forward(reverse_moves, holds: np.ndarray, idx: np.ndarray):
    """The backward moves as a forward plan: each step stitches the patches of ``idx`` it
    holds that no later step (in time) stitches."""
    steps, left = [], np.ones(len(idx), dtype=bool)
    for c in reverse_moves:                              # last hooping in time first
        mine = holds[c, idx] & left
        left &= ~mine
        steps.append((int(c), tuple(int(i) for i in idx[mine])))
    return tuple(reversed(steps))


def _exact(H, T, rank, n):
    """Dijkstra from all-left to none-left over packed single-word states."""
    full = (1 << n) - 1
    big1 = int(rank.max(initial=0)) * n + 1          # one hooping > any rank sum
    big2 = (n + 1) * big1                           # one conflict > any hoopings + ranks
    h = H[:, 0].astype(np.uint64)
    t = T[:, 0].astype(np.uint64)
    best = {full: 0}
    back: dict[int, tuple[int, int]] = {}
    heap = [(0, full)]
    while heap:
        cost, r = heapq.heappop(heap)
        if cost > best.get(r, np.inf):
            continue
        if r == 0:
            break
        rr = np.uint64(r)
        useful = np.flatnonzero((h & rr) != 0)
        conf = np.bitwise_count(t[useful] & rr).astype(np.int64)
        step = conf * big2 + big1 + rank[useful]
        nxt = (np.uint64(r) & ~h[useful]).astype(np.int64)
        for c, s, q in zip(useful.tolist(), step.tolist(), nxt.tolist()):
            new = cost + s
            if new < best.get(q, np.inf):
                best[q] = new
                back[q] = (r, c)
                heapq.heappush(heap, (new, q))
    moves, r = [], 0
    while r != full:
        r, c = back[r]
        moves.append(c)
    return moves[::-1]                                 # from the last hooping in time


def _beam(H, T, rank, width, alpha):
    """Layer-by-layer beam search over packed states (see the module docstring): children
    ranked by conflicts + ``alpha`` x patches left (then patches left, hoop rank); states that
    cannot beat the best finished plan are dropped. Returns (conflicts, moves) or None."""
    start = np.bitwise_or.reduce(H, axis=0)[None, :]     # every patch (each is held)
    conf = np.zeros(1, dtype=np.int64)
    rk = np.zeros(1, dtype=np.int64)
    states, moves = start, [()]
    best = None
    for _layer in range(int(_popcount(start)[0])):
        hit = np.any((states[:, None, :] & H[None, :, :]) != 0, axis=2)          # (B, m)
        b_idx, c_idx = np.nonzero(hit)
        if not len(b_idx):
            break
        c_conf = conf[b_idx] + _popcount(T[c_idx] & states[b_idx])
        c_r = states[b_idx] & ~H[c_idx]
        left = _popcount(c_r)
        c_rank = rk[b_idx] + rank[c_idx]
        keep = np.ones(len(b_idx), dtype=bool) if best is None else c_conf < best[0]
        order = np.lexsort((c_idx, c_rank, left, c_conf + alpha * left))
        order = order[keep[order]]
        done = order[left[order] == 0]
        if len(done):
            j = done[np.lexsort((c_rank[done], c_conf[done]))[0]]
            cand = (int(c_conf[j]), moves[b_idx[j]] + (int(c_idx[j]),))
            if best is None or cand[0] < best[0]:
                best = cand
        order = order[left[order] > 0]
        if best is not None:
            order = order[c_conf[order] < best[0]]
        _, first = np.unique(c_r[order], axis=0, return_index=True)
        order = order[np.sort(first)][:width]
        if not len(order):
            break
        states, conf, rk = c_r[order], c_conf[order], c_rank[order]
        moves = [moves[b_idx[j]] + (int(c_idx[j]),) for j in order]
    return best


def plan_piece(holds: np.ndarray, touches: np.ndarray, rank: np.ndarray, idx: np.ndarray,
               exact_max: int = EXACT_MAX, beam: int = BEAM) -> Plan:
    """The plan of one piece. ``holds``/``touches``: (m, n) bool over all patches, the rows
    restricted to the piece's candidates by the caller (others may be all False); ``rank``:
    (m,) hoop rank of each candidate (0 = smallest); ``idx``: the piece's patch indices."""
    idx = np.asarray(idx, dtype=int)
    rows = np.flatnonzero(holds[:, idx].any(axis=1))
    H = bitsets.pack(holds[np.ix_(rows, idx)])
    T = bitsets.pack(touches[np.ix_(rows, idx)])
    rk = np.asarray(rank, dtype=np.int64)[rows]
    exact = len(idx) <= exact_max
    if exact:
        moves = _exact(H, T, rk, len(idx))
    else:
        found = [_beam(H, T, rk, beam, a) for a in ALPHAS]
        moves = min((f for f in found if f is not None), key=lambda f: (f[0], len(f[1])))[1]
    steps = _forward([int(rows[c]) for c in moves], holds, idx)
    return Plan(steps, plan_cost(steps, touches), exact)
