"""Stitch geometry of a design-file patch: plain, composite (core + surround) or non-circular.

Paper, section 5 ("Design Variations"): "a high-fill central patch can be embedded within a
lower-fill surrounding region to create a functional bistable element with a custom outer
shape". A patch of the design file (``layout.garment.design.PatchSpec``) is therefore one lattice of
equilateral triangles (side ``resolution_mm``, a vertex at the centre) split into regions, each
with its own fill:

* the **core** (only with ``composite``): the lattice cells (whole triangles) whose centroid lies
  in the disc of ``core_diameter_mm``; their stitched area equals ``core_fill`` times the area of
  those cells (the disc rounded to whole cells, so that a core fill of 1 is attainable);
* the **surround**: every other triangle overlapping the outer boundary (the circle of
  ``diameter_mm``, or the ``outline_mm`` polygon); their stitched area equals ``fill`` times the
  area of the outer boundary minus the core cells.

Within a region every triangle is scaled about its centroid by one common factor, solved so
that the region's stitched area (after clipping to the outer boundary) meets its target: the
pipeline ``tessellation.fit_to_fill`` of the plain circular patch (``patch_geometry.make_patch``,
which a spec with neither composite nor outline is). The piece areas here are those of the
stitched polygons (arcs as chords).

A triangle clipped by a non-convex outline can become non-convex or split; it is then cut into
convex parts (constrained Delaunay), because the fill stitches need convex pieces.
"""
from __future__ import annotations

import math

import numpy as np
import shapely

from stitchswitch.errors import InvalidInputError
from stitchswitch.layout.embroidery import tessellation as tess
from stitchswitch.layout.embroidery.patch_geometry import (
    MIN_PIECE_AREA_MM2,
    PatchGeometry,
    conductive_mask,
    make_patch,
    parse_selection,
)

#: the scale search starts just above 0: three coincident points are no polygon for shapely
_LOWEST_SCALE = 1e-9


def geometry_for(spec, resolution_mm: float = 5.0) -> PatchGeometry:
    """The tessellated geometry of one patch spec, centred at the origin (hoop coordinates).
    A conductive selection that selects no triangle is an error (an electrode that is not
    there), so the check's geometry rule reports it before anything is fabricated."""
    geom = _geometry(spec, resolution_mm)
    if spec.conductive and not np.any(geom.conductive):
        raise InvalidInputError(f"patch {spec.id}: conductive {spec.conductive!r} selects no "
                                f"triangle ({geom.n_triangles} triangles at resolution "
                                f"{resolution_mm:g} mm)")
    return geom


def _geometry(spec, resolution_mm: float) -> PatchGeometry:
    selection = parse_selection(spec.conductive) if spec.conductive else None
    composite = getattr(spec, "composite", None)
    outline = getattr(spec, "outline_mm", None)
    if composite is None and outline is None:
        return make_patch(spec.diameter_mm, spec.fill, resolution_mm, selection)
    radius = spec.diameter_mm / 2.0
    if composite is not None and not 0 < composite.core_diameter_mm < spec.diameter_mm:
        raise InvalidInputError(f"patch {spec.id}: core diameter {composite.core_diameter_mm:g} mm "
                                f"must be > 0 and below the diameter {spec.diameter_mm:g} mm")
    if outline is not None:
        _check_outline(spec, np.asarray(outline, dtype=float), radius, composite)
        clip = _PolygonClip(shapely.Polygon(np.asarray(outline, dtype=float)))
    else:
        clip = tess.DiskClip(radius)
    tris = tess.candidates(clip, radius, resolution_mm)
    centroids = tris.mean(axis=1)
    core = np.zeros(len(tris), dtype=bool)
    core_area = 0.0
    if composite is not None:
        rc = composite.core_diameter_mm / 2.0
        core = np.hypot(centroids[:, 0], centroids[:, 1]) < rc
        core_area = float(clip.overlap(tris[core]).sum())
        if not core.any():
            raise InvalidInputError(f"patch {spec.id}: the core ({composite.core_diameter_mm:g} mm) "
                                    f"holds no triangle at resolution {resolution_mm:g} mm")
    regions = [tess.Region(~core, spec.fill * (clip.area_mm2 - core_area))]
    if composite is not None:
        regions.append(tess.Region(core, composite.core_fill * core_area))
    fitted = tess.fit_to_fill(tris, clip, regions, MIN_PIECE_AREA_MM2, _LOWEST_SCALE)
    areas = np.array([tess.polygon_area(p) for p in fitted.pieces_mm])
    lattice_centroids = fitted.centroids_mm[fitted.owner]
    return PatchGeometry(float(spec.diameter_mm), float(spec.fill),
                         float(resolution_mm), float(np.max(fitted.scale)), lattice_centroids,
                         fitted.pieces_mm,
                         conductive_mask(selection, lattice_centroids, resolution_mm),
                         areas, outline_area_mm2=float(clip.area_mm2),
                         piece_scale=fitted.scale[fitted.owner])


def _check_outline(spec, outline: np.ndarray, radius: float, composite) -> None:
    if composite is None:
        raise InvalidInputError(f"patch {spec.id}: a custom outline needs a composite core "
                                "(the circular functional element)")
    if outline.ndim != 2 or outline.shape[1] != 2 or len(outline) < 3:
        raise InvalidInputError(f"patch {spec.id}: outline_mm needs at least 3 (x, y) points")
    boundary = shapely.Polygon(outline)
    if not boundary.is_valid or boundary.area <= 0:
        raise InvalidInputError(f"patch {spec.id}: outline_mm is not a simple polygon")
    far = float(np.hypot(outline[:, 0], outline[:, 1]).max())
    if far > radius * (1 + 1e-9):
        raise InvalidInputError(f"patch {spec.id}: the outline reaches {far:.2f} mm from the centre, "
                                f"beyond the bounding circle of diameter {2 * radius:g} mm")
    core = shapely.Point(0.0, 0.0).buffer(composite.core_diameter_mm / 2.0, quad_segs=64)
    if not boundary.buffer(1e-6).contains(core):
        raise InvalidInputError(f"patch {spec.id}: the core disc ({composite.core_diameter_mm:g} mm) "
                                "is not inside the outline")


class _PolygonClip:
    """A simple polygon (the outline) as a ``tessellation.Clip``; overlaps by shapely."""

    def __init__(self, polygon):
        self.polygon = polygon
        shapely.prepare(polygon)
        self.area_mm2 = float(polygon.area)

    def overlap(self, tris: np.ndarray) -> np.ndarray:
        return shapely.area(shapely.intersection(shapely.polygons(tris), self.polygon))

    def pieces(self, tris: np.ndarray):
        out, owner = [], []
        for i, geom in enumerate(shapely.intersection(shapely.polygons(tris), self.polygon)):
            for part in _convex_parts(geom):
                out.append(part)
                owner.append(i)
        return out, np.asarray(owner, dtype=int)


def _convex_parts(geom) -> list[np.ndarray]:
    """Convex CCW pieces of a clipped triangle (a polygon, or several after a concave cut)."""
    polys = [g for g in getattr(geom, "geoms", [geom]) if g.geom_type == "Polygon" and g.area > 0]
    parts = []
    for poly in polys:
        poly = shapely.orient_polygons(poly)
        if math.isclose(poly.area, poly.convex_hull.area, rel_tol=1e-9):
            parts.append(np.asarray(poly.exterior.coords)[:-1])
            continue
        for tri in shapely.constrained_delaunay_triangles(poly).geoms:
            tri = shapely.orient_polygons(tri)
            parts.append(np.asarray(tri.exterior.coords)[:-1])
    return [p for p in parts if tess.polygon_area(p) >= 1e-9]
