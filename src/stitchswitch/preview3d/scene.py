"""The whole design as geometry: flat pieces, patch surfaces and outlines, in garment mm.

``build_scene(spec)`` looks up every patch's profile, shares the rims between neighbours
(``surfaces.rim_radii_mm``), places each patch in its state and cuts the rims out of the pieces.
``Scene.merged()`` is the one triangle mesh that is rendered and exported: the pieces first, then
the patches in design order, with point data ``height_mm`` (z) and ``patch_index`` (-1 on the
flat fabric). Lines (piece outlines, each patch's embroidery boundary on its surface) are drawn
but not exported.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from stitchswitch.preview3d import fabric, surfaces
from stitchswitch.preview3d.profiles import PatchProfile, patch_profiles
from stitchswitch.preview3d.spec import PreviewSpec


@dataclass(frozen=True, eq=False)
class Part:
    """A triangle mesh; ``patch_index`` is -1 for a piece."""

    name: str
    points: np.ndarray
    triangles: np.ndarray
    patch_index: int


@dataclass(frozen=True, eq=False)
class Line:
    name: str
    kind: str               # "piece" or "patch"
    points: np.ndarray      # (n, 3), closed (last point = first)


@dataclass(frozen=True, eq=False)
class PlacedPatch:
    id: str
    state: str
    profile: PatchProfile
    surface: surfaces.PatchSurface

    @property
    def height_mm(self) -> float:
        """Signed apex height: +h up, -h down."""
        return float(self.surface.points[0, 2])


@dataclass(frozen=True, eq=False)
class Scene:
    pieces: tuple[Part, ...]
    patches: tuple[PlacedPatch, ...]
    lines: tuple[Line, ...]

    @property
    def parts(self) -> tuple[Part, ...]:
        return self.pieces + tuple(Part(p.id, p.surface.points, p.surface.triangles, i)
                                   for i, p in enumerate(self.patches))

    def merged(self):
        """(points (n, 3), triangles (k, 3), point_data) of all parts, pieces first."""
        parts = self.parts
        offsets = np.cumsum([0] + [len(p.points) for p in parts])
        points = np.vstack([p.points for p in parts]) if parts else np.zeros((0, 3))
        tris = (np.vstack([p.triangles + o for p, o in zip(parts, offsets)])
                if parts else np.zeros((0, 3), dtype=int))
        index = np.concatenate([np.full(len(p.points), p.patch_index) for p in parts]) \
            if parts else np.zeros(0, dtype=int)
        return points, tris.astype(np.int64), {"height_mm": points[:, 2].copy(),
                                               "patch_index": index.astype(np.int32)}

    def all_points(self) -> np.ndarray:
        """Every point of every part and line, (n, 3) garment mm (what the camera fits)."""
        pts = [p.points for p in self.parts] + [ln.points for ln in self.lines]
        return np.vstack(pts) if pts else np.zeros((0, 3))


def build_scene(spec: PreviewSpec, n_theta: int = surfaces.N_THETA) -> Scene:
    pats = spec.patches
    profiles = patch_profiles([p.diameter_mm for p in pats], [p.fill for p in pats], spec.material)
    centres = np.array([p.centre_mm for p in pats], dtype=float).reshape(-1, 2)
    rims = surfaces.rim_radii_mm(centres, profiles) if pats else np.zeros(0)
    placed = tuple(
        PlacedPatch(p.id, p.state, prof,
                    surfaces.patch_surface(prof, p.centre_mm, p.state, rim, n_theta))
        for p, prof, rim in zip(pats, profiles, rims))
    holes = [surfaces.rim_polygon(p.centre_mm, rim, n_theta) for p, rim in zip(pats, rims)]
    pieces = []
    lines = []
    for piece in spec.pieces:
        pts, tris = fabric.fabric_mesh(piece.name, piece.outline_mm, holes)
        pieces.append(Part(piece.name, pts, tris, -1))
        ring = np.asarray(piece.outline_mm, dtype=float)
        ring3 = np.column_stack([ring, np.zeros(len(ring))])
        lines.append(Line(piece.name, "piece", np.vstack([ring3, ring3[:1]])))
    for p, prof in zip(pats, profiles):
        lines.append(Line(p.id, "patch", surfaces.boundary_line(
            prof, p.centre_mm, p.state, spec.material.eta, p.outline_mm)))
    return Scene(tuple(pieces), placed, tuple(lines))
