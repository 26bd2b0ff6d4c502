"""The flat garment pieces, with the patch footprints (their rims) cut out, as triangles at z = 0.

Each piece outline minus the union of the patch rim circles is triangulated by a constrained
Delaunay triangulation (``shapely.constrained_delaunay_triangles``, GEOS), so the holes' edges
are the rims' edges and each patch surface meets the flat fabric without a gap.
"""
from __future__ import annotations

import numpy as np
import shapely

from stitchswitch.errors import InvalidInputError


def piece_polygon(name: str, outline_mm: np.ndarray) -> shapely.Polygon:
    ring = np.asarray(outline_mm, dtype=float)
    if ring.ndim != 2 or ring.shape[1] != 2 or len(ring) < 3 or not np.isfinite(ring).all():
        raise InvalidInputError(f"piece {name!r}: outline_mm must be >= 3 finite (x, y) points")
    poly = shapely.Polygon(ring)
    if not poly.is_valid or poly.area <= 0:
        raise InvalidInputError(f"piece {name!r}: outline_mm is not a simple polygon")
    return poly


def triangulate(region) -> tuple[np.ndarray, np.ndarray]:
    """(points (n, 3) at z = 0, triangles (k, 3)) of a (multi)polygon with holes."""
    if region.is_empty:
        return np.zeros((0, 3)), np.zeros((0, 3), dtype=int)
    tris = shapely.get_parts(shapely.constrained_delaunay_triangles(region))
    coords = np.array([np.asarray(t.exterior.coords)[:3] for t in tris]).reshape(-1, 2)
    unique, inverse = np.unique(coords, axis=0, return_inverse=True)
    points = np.column_stack([unique, np.zeros(len(unique))])
    return points, inverse.reshape(-1, 3).astype(int)


def fabric_mesh(name: str, outline_mm: np.ndarray, holes: list[np.ndarray]):
    """The piece minus the hole polygons ((m, 2) garment mm each), triangulated."""
    region = piece_polygon(name, outline_mm)
    if holes:
        region = region.difference(shapely.union_all([shapely.Polygon(h) for h in holes]))
    return triangulate(region)
