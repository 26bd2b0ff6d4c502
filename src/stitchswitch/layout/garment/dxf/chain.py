"""Joining open curves end to end into closed outlines, in O(n log n).

Pattern files draw an outline as many open pieces (Gerber splits the boundary into POLYLINEs;
some exports write every segment as its own LINE) whose ends meet up to a small gap. Two ends
are joined when they are at most the *local* snap tolerance apart: the snap tolerance, but no
more than half the length of the shorter of the two curves, so that an outline drawn with
segments shorter than the tolerance is joined at its true neighbours instead of closing early
on itself. The ends are found with a k-d tree (each end's few nearest ends within the snap
tolerance) and paired greedily, closest pair first; following the pairs from curve to curve
gives the closed rings. An end left without a partner is one error naming where it is, its
gap to the nearest other end and the tolerance that applied there.
"""
from __future__ import annotations

import numpy as np

from stitchswitch.errors import InvalidInputError

#: How many nearest ends of each end are candidates for its partner.
NEIGHBOURS = 8


def curve_length(points: np.ndarray) -> float:
    return float(np.sum(np.hypot(*np.diff(points, axis=0).T)))


def local_tolerance(snap: float, *lengths: float) -> float:
    """The largest gap joined between curves of these lengths (or closing one curve)."""
    return min(snap, 0.5 * min(lengths))


def _pairs(ends: np.ndarray, tol: np.ndarray, snap: float) -> np.ndarray:
    """partner[e] of every end e (-1: none): the greedy closest-first matching of the ends
    closer than the local tolerance of their two curves. End 2i is the start of curve i,
    2i + 1 its end."""
    from scipy.spatial import cKDTree

    n = len(ends)
    k = min(NEIGHBOURS + 1, n)
    dist, idx = cKDTree(ends).query(ends, k=k, distance_upper_bound=snap)
    dist, idx = dist.reshape(n, k), idx.reshape(n, k)
    a = np.repeat(np.arange(n), k)
    b, d = idx.ravel(), dist.ravel()
    ok = (b < n) & (a < b)
    a, b, d = a[ok], b[ok], d[ok]
    ok = d <= np.minimum(tol[a], tol[b])                 # a curve's own two ends close it
    a, b, d = a[ok], b[ok], d[ok]
    partner = np.full(n, -1)
    for i in np.lexsort((b, a, d)):                      # closest first, ties in file order
        if partner[a[i]] < 0 and partner[b[i]] < 0:
            partner[a[i]], partner[b[i]] = b[i], a[i]
    return partner


def chain_loops(fragments: list[np.ndarray], snap: float, where: str, unit: str,
                scale: float) -> list[np.ndarray]:
    """Join polylines end to end into closed rings (no repeated last point), each ring starting
    with the first curve of the file that it holds, in that curve's direction.

    Raises InvalidInputError naming `where` and the gap (converted to mm with `scale`) when an
    end has no partner within the local tolerance, or when a ring has fewer than 3 points.
    """
    n = len(fragments)
    ends = np.array([p for f in fragments for p in (f[0], f[-1])], dtype=float).reshape(-1, 2)
    lengths = np.array([curve_length(f) for f in fragments])
    half = 0.5 * np.repeat(lengths, 2)
    tol = np.minimum(snap, half)
    partner = _pairs(ends, tol, snap)
    lonely = np.flatnonzero(partner < 0)
    if lonely.size:
        _no_partner(int(lonely[0]), ends, tol, snap, where, unit, scale)
    used = np.zeros(n, bool)
    loops = []
    for first in range(n):
        if used[first]:
            continue
        parts, end = [], 2 * first                       # enter curve `first` at its start
        for _ in range(n):
            i, flip = end // 2, end % 2 == 1
            used[i] = True
            f = fragments[i][::-1] if flip else fragments[i]
            parts.append(f if not parts else f[1:])
            out = end ^ 1                                # leave by the curve's other end
            end = int(partner[out])
            if end == 2 * first:
                break
        else:                                            # pragma: no cover - a matching has cycles only
            raise AssertionError("the pairing of curve ends is not a set of cycles")
        ring = np.vstack(parts)[:-1]
        if len(ring) < 3:
            raise InvalidInputError(f"{where}: an outline of {len(ring)} point(s) at "
                                    f"{_fmt(ring[0], unit)} encloses nothing")
        loops.append(ring)
    return loops


def _no_partner(e: int, ends, tol, snap, where, unit, scale):
    from scipy.spatial import cKDTree

    others = np.delete(np.arange(len(ends)), e)
    if others.size == 0:
        raise InvalidInputError(f"{where}: outline cannot be closed: one open curve")
    gap, j = cKDTree(ends[others]).query(ends[e])
    j = int(others[j])
    here = tol[e] if e // 2 == j // 2 else min(tol[e], tol[j])
    limit = ("the snap tolerance" if here >= snap else
             "the tolerance there (half the length of the shorter curve)")
    if gap <= here:
        raise InvalidInputError(
            f"{where}: outline cannot be closed: three or more curve ends meet at "
            f"{_fmt(ends[e], unit)}; an outline must be one chain of curves")
    raise InvalidInputError(
        f"{where}: outline cannot be closed: gap of {gap * scale:.3f} mm between "
        f"{_fmt(ends[e], unit)} and the nearest other curve end {_fmt(ends[j], unit)} exceeds "
        f"{limit} of {here * scale:.3f} mm")


def _fmt(p: np.ndarray, unit: str) -> str:
    return f"({p[0]:.4g}, {p[1]:.4g}) {unit}"
