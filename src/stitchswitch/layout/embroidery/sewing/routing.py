"""The thread's route over the pieces of one thread block: which piece follows which, and how
the thread gets there.

Every piece of a patch is an island (the scaled triangles leave unstitched gaps, the hinges),
so each move from one piece to the next either lays thread across a gap (a *crossing*) or cuts
it (a *trim*): crossings + trims >= pieces - 1 per block, whatever the order. What the route
controls is which gaps are crossed and how often the thread must be cut. It is a path-cover
problem on the *gap graph* (pieces joined when at most ``neighbour_mm`` apart, the weight the
polygon distance, i.e. the shortest crossing); the route is built by Warnsdorff's rule, the
classical heuristic for Hamiltonian paths on grid-like graphs:

* start at the piece nearest the patch centre (centre outward, the usual practice on stretch
  fabric: the fabric is pinned first where it is held best and eased outward);
* move to an unvisited neighbour, preferring a crossing within 20 % of the shortest available,
  then the neighbour with the fewest unvisited neighbours (Warnsdorff: it leaves no stranded
  pieces behind), then the one nearest the centre;
* when no unvisited neighbour is left and the current region (``regions``: groups of pieces
  sewn as one thread, e.g. an electrode) still has unvisited pieces, the route *bridges*
  through the region's already stitched pieces to the nearest of them (shortest path, scipy's
  Dijkstra, on the region's lattice adjacency), so the thread is not cut; otherwise it trims
  and restarts at the innermost unvisited piece (nearest the needle among those within one
  triangle side of the innermost radius). The route never moves from one region to another
  with the thread on.

Every crossing goes straight across the gap at its narrowest (the two pieces' nearest points,
shapely's ``shortest_line``): no crossing between two pieces can be shorter.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import shapely
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components, dijkstra

from stitchswitch.layout.embroidery.planar import length

NEIGHBOUR, BRIDGE, RESTART = "neighbour", "bridge", "restart"


def electrode_regions(centroids_mm: np.ndarray, conductive: np.ndarray,
                      resolution_mm: float) -> list[np.ndarray]:
    """Indices of the conductive pieces of each region (lattice neighbours by a vertex)."""
    idx = np.flatnonzero(conductive)
    if len(idx) == 0:
        return []
    c = centroids_mm[idx]
    d = np.linalg.norm(c[:, None, :] - c[None, :, :], axis=2)
    i, j = np.nonzero(d <= 1.2 * resolution_mm)
    graph = coo_matrix((np.ones(len(i)), (i, j)), shape=(len(idx), len(idx)))
    n, label = connected_components(graph, directed=False)
    return [idx[label == r] for r in range(n)]


@dataclass(frozen=True)
class Step:
    piece: int                      # the piece sewn next
    kind: str                       # NEIGHBOUR, BRIDGE (through ``via``) or RESTART (a trim)
    via: tuple[int, ...] = ()       # BRIDGE: the stitched pieces the thread travels through


def gap_graph(polys, within_mm: float) -> dict[int, dict[int, float]]:
    """Pieces at most ``within_mm`` apart: {i: {j: polygon distance}}."""
    tree = shapely.STRtree(polys)
    left, right = tree.query(polys, predicate="dwithin", distance=within_mm)
    graph: dict[int, dict[int, float]] = {i: {} for i in range(len(polys))}
    keep = left != right
    dist = shapely.distance(polys[left[keep]], polys[right[keep]])
    for i, j, d in zip(left[keep].tolist(), right[keep].tolist(), dist.tolist()):
        graph[i][j] = d
    return graph


def _bridge(polys, region: np.ndarray, centroids, side_mm, current, unvisited) -> list[int]:
    """Pieces from ``current`` to the nearest unvisited piece of ``region`` (inclusive)."""
    members = region.tolist()
    pos = {p: k for k, p in enumerate(members)}
    c = centroids[region]
    d = np.linalg.norm(c[:, None, :] - c[None, :, :], axis=2)
    i, j = np.nonzero((d <= 1.2 * side_mm) & (d > 0))
    w = shapely.distance(polys[region[i]], polys[region[j]]) + 1e-6
    graph = coo_matrix((w, (i, j)), shape=(len(members), len(members))).tocsr()
    dist, pred = dijkstra(graph, indices=pos[current], return_predecessors=True)
    targets = [pos[p] for p in members if p in unvisited]
    target = min(targets, key=lambda t: (dist[t], members[t]))
    if not np.isfinite(dist[target]):          # lattice-disconnected: bridge straight across
        return [current, members[target]]
    path = [target]
    while path[-1] != pos[current]:
        path.append(int(pred[path[-1]]))
    return [members[k] for k in reversed(path)]


def route(pieces_mm, centroids_mm: np.ndarray, centre_mm, side_mm: float, neighbour_mm: float,
          regions: list[np.ndarray] | None = None) -> list[Step]:
    """The visiting order of the pieces and the kind of every move (module docstring).
    ``regions``: index arrays of electrodes, each sewn as one thread (None: no constraint)."""
    n = len(pieces_mm)
    if n == 0:
        return []
    polys = np.array([shapely.Polygon(np.asarray(p, dtype=float)) for p in pieces_mm] + [None],
                     dtype=object)[:-1]
    centroids = np.asarray(centroids_mm, dtype=float)
    radius = np.linalg.norm(centroids - np.asarray(centre_mm, dtype=float), axis=1)
    graph = gap_graph(polys, neighbour_mm)
    region_of = np.full(n, -1)
    for r, members in enumerate(regions or []):
        region_of[members] = r
    unvisited = set(range(n))
    degree = np.array([len(graph[i]) for i in range(n)])

    def visit(i):
        unvisited.discard(i)
        for j in graph[i]:
            degree[j] -= 1

    def restart(needle):
        inner = min(radius[i] for i in unvisited)
        band = [i for i in sorted(unvisited) if radius[i] <= inner + side_mm]
        if needle is None:
            return min(band, key=lambda i: (radius[i], i))
        return min(band, key=lambda i: (length(centroids[i] - centroids[needle]), i))

    cur = restart(None)
    steps = [Step(cur, RESTART)]
    visit(cur)
    while unvisited:
        r = region_of[cur]
        # never from one electrode to another (nor into the normal thread's pieces)
        options = [j for j in graph[cur] if j in unvisited and region_of[j] == r]
        if options:
            best = min(graph[cur][j] for j in options)
            nxt = min(options, key=lambda j: (graph[cur][j] > 1.2 * best + 1e-9, degree[j],
                                              round(radius[j], 6), j))
            steps.append(Step(nxt, NEIGHBOUR))
        elif r >= 0 and _left(region_of, r, unvisited):
            path = _bridge(polys, regions[r], centroids, side_mm, cur, unvisited)
            nxt = path[-1]
            steps.append(Step(nxt, BRIDGE, tuple(path[1:-1])))
        else:
            nxt = restart(cur)
            steps.append(Step(nxt, RESTART))
        visit(nxt)
        cur = nxt
    return steps


def _left(region_of: np.ndarray, r: int, unvisited: set) -> bool:
    return any(region_of[i] == r for i in unvisited)


def crossing(a: np.ndarray, b: np.ndarray, min_stitch_mm: float) -> tuple[np.ndarray, np.ndarray]:
    """The needle points of the shortest crossing from piece ``a`` to piece ``b``: their nearest
    points, each moved back into its own piece when the gap is narrower than a stitch may be
    short (the thread outside the pieces stays the gap width)."""
    line = shapely.shortest_line(shapely.Polygon(a), shapely.Polygon(b))
    p, q = np.asarray(line.coords, dtype=float)
    gap = length(q - p)
    short = min_stitch_mm + 0.05 - gap
    if short > 0 and gap > 1e-9:
        u = (q - p) / gap
        p, q = _inward(a, p, -u, short / 2), _inward(b, q, u, short / 2)
    return p, q


def _inward(poly: np.ndarray, p: np.ndarray, direction: np.ndarray, step: float) -> np.ndarray:
    """``p`` moved by ``step`` along ``direction`` if that stays in the piece, else toward its
    centroid (a corner of a sliver)."""
    shape = shapely.Polygon(poly).buffer(1e-9)
    q = p + direction * step
    if shape.covers(shapely.Point(q)):
        return q
    c = np.asarray(poly, dtype=float).mean(axis=0)
    d = c - p
    n = length(d)
    return p + d / n * min(step, n) if n > 0 else p
