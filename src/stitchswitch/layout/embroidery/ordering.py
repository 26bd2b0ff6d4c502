"""A short, deterministic visiting order: nearest neighbour, then 2-opt (open path)."""
from __future__ import annotations

import numpy as np


def path_length(points: np.ndarray, order: np.ndarray) -> float:
    """Length of the open path through ``points`` in ``order``."""
    p = points[order]
    return float(np.linalg.norm(np.diff(p, axis=0), axis=1).sum())


def nearest_neighbour(points: np.ndarray, start: int) -> np.ndarray:
    """Greedy tour from ``start``; ties go to the lowest index (deterministic)."""
    n = len(points)
    visited = np.zeros(n, dtype=bool)
    order = np.empty(n, dtype=int)
    cur = start
    for k in range(n):
        order[k] = cur
        visited[cur] = True
        if k == n - 1:
            break
        d = np.hypot(points[:, 0] - points[cur, 0], points[:, 1] - points[cur, 1])
        d[visited] = np.inf
        cur = int(np.argmin(d))
    return order


def two_opt(points: np.ndarray, order: np.ndarray, max_passes: int = 30) -> np.ndarray:
    """Improve an open path by segment reversals until no reversal shortens it (or
    ``max_passes`` sweeps). For each i the best j is applied; the sweep order is fixed."""
    order = order.copy()
    n = len(order)
    if n < 4:
        return order
    for _ in range(max_passes):
        improved = False
        for i in range(n - 2):
            p = points[order]
            a, b = p[i], p[i + 1]
            c = p[i + 2:]                       # candidates j = i+2 .. n-1
            e = np.vstack([p[i + 3:], [[np.nan, np.nan]]])
            d_ab = np.hypot(*(a - b))
            d_ce = np.hypot(c[:, 0] - e[:, 0], c[:, 1] - e[:, 1])
            d_ac = np.hypot(c[:, 0] - a[0], c[:, 1] - a[1])
            d_be = np.hypot(e[:, 0] - b[0], e[:, 1] - b[1])
            last = np.isnan(d_ce)
            d_ce[last] = 0.0
            d_be[last] = 0.0
            gain = d_ab + d_ce - d_ac - d_be
            j = int(np.argmax(gain))
            if gain[j] > 1e-9:
                jj = i + 2 + j
                order[i + 1:jj + 1] = order[i + 1:jj + 1][::-1]
                improved = True
        if not improved:
            break
    return order


def visiting_order(points: np.ndarray) -> np.ndarray:
    """Nearest neighbour from the lowest, then leftmost point, improved by 2-opt."""
    points = np.asarray(points, dtype=float)
    if len(points) == 0:
        return np.zeros(0, dtype=int)
    start = int(np.lexsort((points[:, 0], points[:, 1]))[0])
    return two_opt(points, nearest_neighbour(points, start))
