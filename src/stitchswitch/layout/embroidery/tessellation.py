"""The regular tessellation of the plane by equilateral triangles, its clipping to a region, and
its scaling to a fill.

Coordinates are hoop (stretched-fabric) coordinates in mm, x to the right, y up, origin at the
patch centre (docs/embroidery.md). The lattice has a vertex at the origin and horizontal rows, so
every triangle has one horizontal edge and the pattern has the six-fold symmetry of the patch.

``fit_to_fill`` is the one pipeline every patch goes through (plain circles in
``patch_geometry``, composite and outlined patches in ``patch_design``): the lattice triangles
of each region are scaled about their centroids by the region's common factor, solved so that
their area inside the clip region meets the region's target, slivers too small to stitch are
dropped (and the factor solved again), and the scaled triangles are clipped to the region.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Protocol

import numpy as np
from scipy.optimize import brentq

from stitchswitch.layout.embroidery.planar import dot

SQRT3 = math.sqrt(3.0)


def lattice_triangles(radius_mm: float, side_mm: float) -> np.ndarray:
    """All lattice triangles (counter-clockwise, shape (n, 3, 2)) that overlap the disk of
    ``radius_mm`` about the origin, ordered by row (bottom to top) then by x."""
    h = side_mm * SQRT3 / 2.0
    n_rows = int(math.ceil(radius_mm / h)) + 1
    n_cols = int(math.ceil(radius_mm / side_mm)) + 2
    tris = []
    for j in range(-n_rows, n_rows):
        y0, y1 = j * h, (j + 1) * h
        shift = 0.5 * side_mm * (j % 2)          # odd rows start half a side to the right
        for i in range(-n_cols, n_cols + 1):
            x = i * side_mm + shift
            tris.append(((x, y0), (x + side_mm, y0), (x + 0.5 * side_mm, y1)))          # up
            tris.append(((x + 0.5 * side_mm, y1), (x - 0.5 * side_mm, y1), (x, y0)))   # down
    t = np.asarray(tris, dtype=float)
    keep = disk_overlap_area(t, radius_mm) > 1e-12 * side_mm ** 2
    t = t[keep]
    c = t.mean(axis=1)
    order = np.lexsort((np.round(c[:, 0], 9), np.round(c[:, 1], 9)))
    return t[order]


def _segment_disk_area(a: np.ndarray, b: np.ndarray, r: float) -> np.ndarray:
    """Signed area of (triangle O, a, b) intersected with the disk of radius r about O.

    Vectorised over the leading axis; the classic building block of polygon/circle overlap."""
    d = b - a
    A = np.einsum("ij,ij->i", d, d)
    B = np.einsum("ij,ij->i", a, d)
    C = np.einsum("ij,ij->i", a, a) - r * r
    disc = np.maximum(B * B - A * C, 0.0)
    sq = np.sqrt(disc)
    with np.errstate(divide="ignore", invalid="ignore"):
        t1 = np.where(A > 0, (-B - sq) / A, 0.0)
        t2 = np.where(A > 0, (-B + sq) / A, 0.0)
    t1 = np.clip(t1, 0.0, 1.0)
    t2 = np.clip(t2, 0.0, 1.0)
    t2 = np.maximum(t1, t2)
    p1 = a + t1[:, None] * d
    p2 = a + t2[:, None] * d

    def sector(u, v):
        cross = u[:, 0] * v[:, 1] - u[:, 1] * v[:, 0]
        dot = np.einsum("ij,ij->i", u, v)
        return 0.5 * r * r * np.arctan2(cross, dot)

    def tri(u, v):
        return 0.5 * (u[:, 0] * v[:, 1] - u[:, 1] * v[:, 0])

    return sector(a, p1) + tri(p1, p2) + sector(p2, b)


def disk_overlap_area(polys: np.ndarray, radius_mm: float) -> np.ndarray:
    """Exact area of each counter-clockwise convex polygon (shape (n, k, 2)) inside the disk."""
    n, k, _ = polys.shape
    total = np.zeros(n)
    for e in range(k):
        total += _segment_disk_area(polys[:, e], polys[:, (e + 1) % k], radius_mm)
    return total


def polygon_area(poly: np.ndarray) -> float:
    """Shoelace area of a closed polygon given as (k, 2) vertices (positive if CCW)."""
    x, y = poly[:, 0], poly[:, 1]
    return 0.5 * float(np.sum(x * np.roll(y, -1)) - np.sum(y * np.roll(x, -1)))


def clip_to_disk(poly: np.ndarray, radius_mm: float, arc_step_mm: float = 0.1) -> np.ndarray:
    """The convex CCW polygon ``poly`` intersected with the disk, arcs as chords of at most
    ``arc_step_mm``. Returns an (m, 2) array; m == 0 if they do not overlap."""
    r = radius_mm
    r2_in = r * r * (1.0 - 1e-12)
    d2 = np.einsum("ij,ij->i", poly, poly)
    if (d2 <= r * r * (1.0 + 1e-12)).all():
        return poly.copy()
    inside = d2 < r2_in
    events = []   # (point, kind): "v" vertex strictly inside, "in"/"out" circle crossings
    k = len(poly)
    for e in range(k):
        a, b = poly[e], poly[(e + 1) % k]
        if inside[e]:
            events.append((a, "v"))
        d = b - a
        A, B, C = dot(d, d), dot(a, d), dot(a, a) - r * r
        disc = B * B - A * C
        if A <= 0 or disc <= 0:
            continue
        sq = math.sqrt(disc)
        for t in sorted(((-B - sq) / A, (-B + sq) / A)):
            if 0.0 <= t < 1.0:
                # the sign of d|a + t d|^2/dt says whether the edge leaves or enters the disk
                events.append((a + t * d, "out" if B + t * A > 0 else "in"))
    if not events:
        # no vertex inside and no crossing: disjoint, or the disk lies inside the polygon
        return _circle(r, arc_step_mm) if _contains_origin(poly) else np.zeros((0, 2))
    out = []
    m = len(events)
    for idx, (p, kind) in enumerate(events):
        out.append(p)
        if kind == "out":
            q = events[(idx + 1) % m][0]
            a0 = math.atan2(p[1], p[0])
            a1 = math.atan2(q[1], q[0])
            sweep = (a1 - a0) % (2 * math.pi)
            n_seg = max(1, int(math.ceil(sweep * r / arc_step_mm)))
            for s in range(1, n_seg):
                ang = a0 + sweep * s / n_seg
                out.append(np.array([r * math.cos(ang), r * math.sin(ang)]))
    return np.asarray(out)


def _circle(r: float, step: float) -> np.ndarray:
    n = max(12, int(math.ceil(2 * math.pi * r / step)))
    ang = 2 * math.pi * np.arange(n) / n
    return np.column_stack([r * np.cos(ang), r * np.sin(ang)])


def _contains_origin(poly: np.ndarray) -> bool:
    k = len(poly)
    for e in range(k):
        a, b = poly[e], poly[(e + 1) % k]
        if (b[0] - a[0]) * (-a[1]) - (b[1] - a[1]) * (-a[0]) < 0:
            return False
    return True


# --- clipping regions ------------------------------------------------------------------------

class Clip(Protocol):
    """The outer boundary a patch is clipped to."""
    area_mm2: float

    def overlap(self, polys: np.ndarray) -> np.ndarray:
        """Area inside the region of each CCW convex polygon of ``polys`` (shape (n, k, 2))."""

    def pieces(self, polys: np.ndarray) -> tuple[list[np.ndarray], np.ndarray]:
        """The convex CCW pieces of ``polys`` inside the region, and the index of the polygon
        each piece comes from."""


@dataclass(frozen=True)
class DiskClip:
    """The disk of ``radius_mm`` about the origin, with exact overlap areas."""
    radius_mm: float

    @property
    def area_mm2(self) -> float:
        return math.pi * self.radius_mm * self.radius_mm

    def overlap(self, polys: np.ndarray) -> np.ndarray:
        return disk_overlap_area(polys, self.radius_mm)

    def pieces(self, polys: np.ndarray) -> tuple[list[np.ndarray], np.ndarray]:
        return [clip_to_disk(t, self.radius_mm) for t in polys], np.arange(len(polys))


def candidates(clip: Clip, radius_mm: float, side_mm: float) -> np.ndarray:
    """The lattice triangles (``lattice_triangles`` order) that overlap ``clip``, a region
    inside the disk of ``radius_mm``."""
    tris = lattice_triangles(radius_mm, side_mm)
    return tris[clip.overlap(tris) > 1e-12 * side_mm ** 2]


# --- scaling to a fill ------------------------------------------------------------------------

@dataclass(frozen=True)
class Region:
    """Candidate triangles (``mask``) sewn at one common scale factor, whose stitched area
    inside the clip must be ``target_area_mm2``."""
    mask: np.ndarray
    target_area_mm2: float


@dataclass(frozen=True)
class FittedLattice:
    """The candidates kept by ``fit_to_fill``, scaled and clipped."""
    triangles_mm: np.ndarray            # (m, 3, 2) the kept lattice triangles, candidate order
    scale: np.ndarray                   # (m,) the scale factor of each kept triangle
    region_scales: tuple[float, ...]    # the common factor of each region, in ``regions`` order
    scaled_mm: np.ndarray               # (m, 3, 2) each kept triangle scaled about its centroid
    pieces_mm: tuple[np.ndarray, ...]   # convex CCW pieces: the scaled triangles clipped
    owner: np.ndarray                   # (k,) the kept triangle each piece comes from

    @property
    def centroids_mm(self) -> np.ndarray:
        """(m, 2) centroids of the kept lattice triangles (those of the scaled ones too)."""
        return self.triangles_mm.mean(axis=1)


def fit_to_fill(tris: np.ndarray, clip: Clip, regions: list[Region],
                min_piece_area_mm2: float, lowest_scale: float = 0.0) -> FittedLattice:
    """Scale each region's triangles by one factor s in [``lowest_scale``, 1] so that their
    area inside ``clip`` is the region's target (s = 1 if even the whole triangles fall short),
    drop the pieces under ``min_piece_area_mm2`` (they cannot be stitched) and solve again, so
    that the target holds for what is sewn; then clip the scaled triangles."""
    keep = np.ones(len(tris), dtype=bool)
    scale = np.ones(len(tris))
    region_scales = []
    for region in regions:
        idx = np.flatnonzero(region.mask)
        s = _solve_scale(tris[idx], clip, region.target_area_mm2, lowest_scale)
        for _ in range(5):   # converges in 1-2 rounds
            small = clip.overlap(_scaled(tris[idx], s)) < min_piece_area_mm2
            if not small.any():
                break
            keep[idx[small]] = False
            idx = idx[~small]
            s = _solve_scale(tris[idx], clip, region.target_area_mm2, lowest_scale)
        scale[idx] = s
        region_scales.append(float(s))
    tris, scale = tris[keep], scale[keep]
    c = tris.mean(axis=1)
    scaled = c[:, None, :] + scale[:, None, None] * (tris - c[:, None, :])
    pieces, owner = clip.pieces(scaled)
    return FittedLattice(tris, scale, tuple(region_scales), scaled, tuple(pieces), owner)


def _scaled(tris: np.ndarray, s: float) -> np.ndarray:
    c = tris.mean(axis=1, keepdims=True)
    return c + s * (tris - c)


def _solve_scale(tris: np.ndarray, clip: Clip, target: float, lowest: float) -> float:
    f = lambda s: float(clip.overlap(_scaled(tris, s)).sum()) - target  # noqa: E731
    if f(1.0) <= 0.0:
        return 1.0
    return brentq(f, lowest, 1.0, xtol=1e-12, rtol=1e-12)
