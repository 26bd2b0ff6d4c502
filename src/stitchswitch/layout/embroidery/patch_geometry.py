"""Patch geometry: a circle of diameter d tiled by equilateral triangles, scaled to fill p.

Rule for the triangles cut by the circle (docs/embroidery.md):

1. Every triangle of the lattice (side ``resolution_mm``) that overlaps the disk is a candidate.
2. Each triangle is scaled uniformly about its own centroid by one common factor ``s`` and the
   scaled triangle is clipped to the circle (the patch outline cuts the stitched triangles).
3. ``s`` is solved (Brent's method on the exact triangle/disk overlap area) so that the stitched
   area divided by the patch area pi d^2/4 equals the fill p.
4. Pieces smaller than ``min_piece_area_mm2`` cannot be stitched; they are dropped and ``s`` is
   solved again on the remaining triangles, so the identity of step 3 holds for what is sewn.
   (At p = 1, s is capped at 1: the dropped slivers are then the whole, reported, deficit.)

Interior triangles are therefore exactly similar, scaled copies of the lattice triangles, and the
fill holds for any resolution, not only in the limit of small triangles. Steps 2-4 are
``tessellation.fit_to_fill``, which composite and outlined patches (``patch_design``) share.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from stitchswitch.errors import InvalidInputError
from stitchswitch.files.shown import clip, show
from stitchswitch.layout.embroidery import tessellation as tess

DIAMETER_RANGE_MM = (5.0, 360.0)
RESOLUTION_RANGE_MM = (1.0, 30.0)
#: pieces smaller than this cannot be stitched and are dropped (step 4 of the rule)
MIN_PIECE_AREA_MM2 = 0.1


# --- conductive selections ----------------------------------------------------------------

@dataclass(frozen=True)
class ByIndex:
    """Triangles by index (``PatchGeometry.centroids_mm`` order)."""
    indices: tuple[int, ...]

    def select(self, centroids_mm: np.ndarray, resolution_mm: float) -> np.ndarray:
        n = len(centroids_mm)
        bad = [i for i in self.indices if not 0 <= i < n]
        if bad:
            raise InvalidInputError(f"conductive triangle index {bad[0]} is outside 0..{n - 1}")
        mask = np.zeros(n, dtype=bool)
        mask[list(self.indices)] = True
        return mask


@dataclass(frozen=True)
class ByRing:
    """Triangles by ring: ring k holds the centroids at distance [k w, (k+1) w) from the centre,
    with w = the lattice row height resolution * sqrt(3)/2."""
    rings: tuple[int, ...]

    def select(self, centroids_mm: np.ndarray, resolution_mm: float) -> np.ndarray:
        w = resolution_mm * tess.SQRT3 / 2.0
        ring = np.floor(np.hypot(centroids_mm[:, 0], centroids_mm[:, 1]) / w + 1e-9).astype(int)
        return np.isin(ring, list(self.rings))


@dataclass(frozen=True)
class ByAnnulus:
    """Triangles whose centroid lies at a distance in [inner_radius_mm, outer_radius_mm)."""
    inner_radius_mm: float
    outer_radius_mm: float

    def __post_init__(self):
        if not 0 <= self.inner_radius_mm < self.outer_radius_mm:
            raise InvalidInputError(f"annulus radii {self.inner_radius_mm:g}, "
                                    f"{self.outer_radius_mm:g} mm need 0 <= inner < outer")

    def select(self, centroids_mm: np.ndarray, resolution_mm: float) -> np.ndarray:
        r = np.hypot(centroids_mm[:, 0], centroids_mm[:, 1])
        return (r >= self.inner_radius_mm) & (r < self.outer_radius_mm)


@dataclass(frozen=True)
class ByPolygon:
    """Triangles whose centroid lies inside a polygon (even-odd rule), vertices in mm."""
    vertices_mm: tuple[tuple[float, float], ...]

    def __post_init__(self):
        if len(self.vertices_mm) < 3:
            raise InvalidInputError("a conductive polygon needs at least 3 vertices")

    def select(self, centroids_mm: np.ndarray, resolution_mm: float) -> np.ndarray:
        v = np.asarray(self.vertices_mm, dtype=float)
        x, y = centroids_mm[:, 0], centroids_mm[:, 1]
        inside = np.zeros(len(centroids_mm), dtype=bool)
        for (x0, y0), (x1, y1) in zip(v, np.roll(v, -1, axis=0)):
            crosses = (y0 > y) != (y1 > y)
            with np.errstate(divide="ignore", invalid="ignore"):
                xc = x0 + (y - y0) * (x1 - x0) / (y1 - y0)
            inside ^= crosses & (x < xc)
        return inside


Selection = ByIndex | ByRing | ByAnnulus | ByPolygon


# --- the patch --------------------------------------------------------------------------

@dataclass(frozen=True)
class PatchGeometry:
    """A tessellated circular patch in hoop coordinates (mm, centre at the origin)."""
    diameter_mm: float
    fill: float
    resolution_mm: float
    scale: float                      # the common triangle scale factor s
    centroids_mm: np.ndarray          # (n, 2) centroids of the (full) lattice triangles
    pieces_mm: tuple[np.ndarray, ...]  # n convex CCW polygons: scaled triangles clipped to the circle
    conductive: np.ndarray            # (n,) bool: stitched in the second (conductive) thread
    areas_mm2: np.ndarray = field(repr=False)   # (n,) exact area of each piece
    #: area of a non-circular outer boundary (``layout.embroidery.patch_design``); None: the circle
    outline_area_mm2: float | None = None
    #: (n,) scale factor of each piece where regions differ (composite patches); None: ``scale``
    piece_scale: np.ndarray | None = field(default=None, repr=False)

    @property
    def patch_area_mm2(self) -> float:
        if self.outline_area_mm2 is not None:
            return self.outline_area_mm2
        return math.pi * self.diameter_mm ** 2 / 4.0

    @property
    def stitched_area_mm2(self) -> float:
        return float(self.areas_mm2.sum())

    @property
    def achieved_fill(self) -> float:
        return self.stitched_area_mm2 / self.patch_area_mm2

    @property
    def n_triangles(self) -> int:
        return len(self.pieces_mm)


def conductive_mask(selection: Selection | None, centroids_mm: np.ndarray,
                    resolution_mm: float) -> np.ndarray:
    """The pieces (given by the centroids of their lattice triangles) in the conductive thread."""
    if selection is None:
        return np.zeros(len(centroids_mm), dtype=bool)
    return selection.select(centroids_mm, resolution_mm)


def make_patch(diameter_mm: float, fill: float, resolution_mm: float = 5.0,
               conductive: Selection | None = None,
               min_piece_area_mm2: float = MIN_PIECE_AREA_MM2) -> PatchGeometry:
    """Tessellate a circular patch of ``diameter_mm`` at ``fill`` (see the module docstring);
    the piece areas are the exact overlaps of the scaled triangles with the disk."""
    for name, v in (("diameter", diameter_mm), ("fill", fill), ("resolution", resolution_mm)):
        if not isinstance(v, (int, float)) or not math.isfinite(v):
            raise InvalidInputError(f"{name} {v!r} is not a finite number")
    if not DIAMETER_RANGE_MM[0] <= diameter_mm <= DIAMETER_RANGE_MM[1]:
        raise InvalidInputError(f"diameter {diameter_mm:g} mm is outside "
                                f"[{DIAMETER_RANGE_MM[0]:g}, {DIAMETER_RANGE_MM[1]:g}] mm")
    if not 0.0 < fill <= 1.0:
        raise InvalidInputError(f"fill {fill:g} is outside (0, 1]")
    if not RESOLUTION_RANGE_MM[0] <= resolution_mm <= RESOLUTION_RANGE_MM[1]:
        raise InvalidInputError(f"resolution {resolution_mm:g} mm is outside "
                                f"[{RESOLUTION_RANGE_MM[0]:g}, {RESOLUTION_RANGE_MM[1]:g}] mm")
    if resolution_mm > diameter_mm:
        raise InvalidInputError(f"resolution {resolution_mm:g} mm is coarser than the "
                                f"diameter {diameter_mm:g} mm: no tessellation")
    radius = diameter_mm / 2.0
    disk = tess.DiskClip(radius)
    tris = tess.candidates(disk, radius, resolution_mm)
    whole = tess.Region(np.ones(len(tris), dtype=bool), fill * math.pi * radius ** 2)
    fitted = tess.fit_to_fill(tris, disk, [whole], min_piece_area_mm2)
    centroids = fitted.centroids_mm
    return PatchGeometry(float(diameter_mm), float(fill), float(resolution_mm),
                         fitted.region_scales[0], centroids, fitted.pieces_mm,
                         conductive_mask(conductive, centroids, resolution_mm),
                         disk.overlap(fitted.scaled_mm))


def parse_selection(spec: str) -> Selection:
    """A selection from text: ``index:0,5,7``, ``ring:0,1``, ``annulus:INNER:OUTER`` (mm) or
    ``polygon:x,y;x,y;x,y`` (mm)."""
    kind, _, rest = str(spec).partition(":")
    kind = kind.strip().lower()
    try:
        if kind == "index":
            return ByIndex(tuple(int(v) for v in rest.split(",") if v.strip()))
        if kind == "ring":
            return ByRing(tuple(int(v) for v in rest.split(",") if v.strip()))
        if kind == "annulus":
            inner, outer = (float(v) for v in rest.split(":"))
            return ByAnnulus(inner, outer)
        if kind == "polygon":
            return ByPolygon(tuple(tuple(float(c) for c in p.split(",")) for p in rest.split(";")))
    except ValueError as exc:
        if isinstance(exc, InvalidInputError):
            raise
        raise InvalidInputError(f"cannot read the selection {show(spec)}: {clip(str(exc), 80)}") from None
    raise InvalidInputError(f"unknown selection {show(spec)}; use index:I,J,..., ring:K,..., "
                            "annulus:INNER:OUTER or polygon:X,Y;X,Y;...")
