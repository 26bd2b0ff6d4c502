"""Greedy hoop grouping: the baselines and the fallback of the MIP (docs/fabrication.md).

Garment mode works on the candidate placements of ``candidates`` (columns):

* ``greedy_cover``: the classic greedy set cover. Repeatedly take the candidate holding the most
  patches not yet held; ties: less frame overlap, smaller hoop, lower index.
* ``first_fit_decreasing_garment``: patches by decreasing diameter (then input order); each goes
  into the first open hooping that, with it, is still held by some candidate (the hooping's
  hoop may grow), otherwise it opens a hooping with the smallest hoop that holds it. Among the
  candidates holding a hooping's set the smallest hoop, then the least overlap, then the lowest
  index is used.

Free mode works on circles (``circle_packing``):

* ``first_fit_decreasing_free``: patches by decreasing diameter; each goes into the first open
  hoop where ``circle_packing.place`` finds room for it (the hoop's discs were placed in
  decreasing order too, so repacking would replay the same placements), otherwise into a new
  hoop of type ``open_hoop`` (default: the largest short side, then the largest area); at the
  end every hoop is shrunk to the smallest hoop type its patches can be repacked into.

Every function returns plain index lists so that the MIP and the heuristics are compared on
exactly the same data.
"""
from __future__ import annotations

import numpy as np

from stitchswitch.layout.fabrication.grouping import bitsets
from stitchswitch.layout.fabrication.grouping import circle_packing as cpk


def _tie_order(cands) -> np.ndarray:
    """Candidate preference for ties: smaller hoop, less overlap, lower index."""
    area = np.array([cands.hoops[k].area_mm2 for k in cands.hoop_index])
    return np.lexsort((np.arange(len(area)), cands.overlap, area))


def greedy_cover(cands) -> list[int]:
    """Greedy set cover over the candidates (indices of the chosen ones, in pick order)."""
    holds = cands.holds
    left = holds.any(axis=0)
    rank = np.empty(len(cands), dtype=int)
    rank[_tie_order(cands)] = np.arange(len(cands))
    chosen = []
    while left.any():
        gain = holds[:, left].sum(axis=1)
        best = gain.max()
        if best == 0:
            break
        tied = np.flatnonzero(gain == best)
        c = int(tied[np.argmin(rank[tied])])
        chosen.append(c)
        left &= ~holds[c]
    return chosen


def first_fit_decreasing_garment(cands, diameters) -> list[int]:
    """First-fit decreasing over the candidates (indices, one per hooping)."""
    n = cands.holds.shape[1]
    rows = bitsets.pack(cands.holds)
    pref = _tie_order(cands)
    order = np.lexsort((np.arange(n), -np.asarray(diameters, dtype=float)))
    bins: list[tuple[np.ndarray, int]] = []     # (member mask, candidate)

    def best_for(mask):
        ok = bitsets.supersets(rows, bitsets.pack(mask[None, :])[0])
        hits = pref[ok[pref]]
        return int(hits[0]) if len(hits) else None

    for i in order:
        if not cands.holds[:, i].any():
            continue
        for b, (mask, _) in enumerate(bins):
            trial = mask.copy()
            trial[i] = True
            c = best_for(trial)
            if c is not None:
                bins[b] = (trial, c)
                break
        else:
            mask = np.zeros(n, dtype=bool)
            mask[i] = True
            bins.append((mask, best_for(mask)))
    return [c for _, c in bins]


def fits(radii, w: float, h: float):
    """Centres packing ``radii`` (decreasing order) into w x h, or None."""
    order = np.lexsort((np.arange(len(radii)), -np.asarray(radii)))
    got = cpk.pack(np.asarray(radii)[order], w, h)
    if got is None:
        return None
    out = np.empty_like(got)
    out[order] = got
    return out


def first_fit_decreasing_free(radii, containers, open_hoop: int | None = None,
                              shrink: bool = True):
    """First-fit decreasing of circles (radii already grown by half the spacing) into
    containers [(w, h) per hoop type]. Returns [(hoop type, member indices, centres)]; with
    ``shrink`` False every hoop stays of type ``open_hoop``."""
    radii = np.asarray(radii, dtype=float)
    areas = [w * h for w, h in containers]
    big = (max(range(len(containers)), key=lambda t: (min(containers[t]), areas[t]))
           if open_hoop is None else open_hoop)
    order = np.lexsort((np.arange(len(radii)), -radii))
    bins: list[list] = []                        # [members, centres]
    W, H = containers[big]
    for i in order:
        for b in bins:
            if np.sum(radii[b[0]] ** 2) + radii[i] ** 2 > W * H / np.pi:
                continue                         # more disc area than the container
            p = cpk.pack([radii[i]], W, H, b[1], radii[b[0]])
            if p is None:
                continue
            b[0].append(int(i))
            b[1] = np.vstack([b[1], p])
            break
        else:
            p = cpk.pack([radii[i]], W, H)
            if p is None:
                return None
            bins.append([[int(i)], p])
    out = []
    by_area = np.argsort(areas, kind="stable") if shrink else []
    for members, centres in bins:
        best = (big, centres)
        for t in by_area:
            if areas[t] >= areas[big]:
                break
            p = fits(radii[members], *containers[t])
            if p is not None:
                best = (int(t), p)
                break
        out.append((best[0], tuple(members), best[1]))
    return out
