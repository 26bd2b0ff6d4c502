"""The whole design as geometry: flat pieces, patch surfaces and outlines, in garment mm.

``build_scene(spec)`` looks up every patch's profile, shares the rims between neighbours
(``surfaces.rim_radii_mm``), places each patch in its state and cuts the rims out of the pieces.
``Scene.merged()`` is the one triangle mesh that is rendered and exported: the pieces first, then
the patches in design order, with point data ``height_mm`` (z) and ``patch_index`` (-1 on the
flat fabric). Lines (piece outlines, each patch's embroidery boundary on its surface) are drawn
but not exported.

``SceneBuilder`` is the builder itself (``build_scene`` is one use of it): it keeps the parts
of the last scene it built and rebuilds only those whose inputs changed: a patch surface when
its design, centre, state or rim changed (a neighbour moving closer changes the rim), its
boundary line when its design, centre, state or outline changed, a piece when its outline or
one of the rim holes on it changed, and profiles only for designs it has not looked up yet. A
reused part is the same object as in the previous scene, so a view can tell what to resend by
identity. Rebuilding from scratch and rebuilding incrementally give the same scene, array for
array (tests/test_studio_scene.py).
"""
from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np

from stitchswitch.errors import InvalidInputError
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


#: profiles kept by a ``SceneBuilder`` between builds (a slider swept back and forth)
PROFILE_CACHE_SIZE = 512


def _hole_on(piece_bounds, centre_mm, rim_mm: float) -> bool:
    """Whether the rim circle can touch the piece (its box meets the piece's bounding box)."""
    x0, y0, x1, y1 = piece_bounds
    cx, cy = centre_mm
    return cx + rim_mm >= x0 and cx - rim_mm <= x1 and cy + rim_mm >= y0 and cy - rim_mm <= y1


def thinned(profile: PatchProfile, step: int) -> PatchProfile:
    """The profile drawn with every ``step``-th node (and the nodes the surface is placed by:
    the pole, the embroidery boundary, keypoint b and the node after it, the last node), for a
    lighter mesh; ``step`` 1 is the profile itself. The apex, R_b and the blend start are
    unchanged, so the drawn height and footprint are the model's."""
    if step == 1:
        return profile
    n, b = profile.R_mm.size, profile.keypoints.b_index
    keep = np.unique(np.concatenate([np.arange(0, n, step),
                                     [profile.n_inside, b, min(b + 1, n - 1), n - 1]]))
    where = {int(k): i for i, k in enumerate(keep)}
    return dataclasses.replace(
        profile, R_mm=profile.R_mm[keep], r_mm=profile.r_mm[keep], z_mm=profile.z_mm[keep],
        n_inside=where[profile.n_inside],
        keypoints=dataclasses.replace(profile.keypoints, b_index=where[b]))


class SceneBuilder:
    """Builds the scenes of successive specs, reusing every part whose inputs did not change
    (module docstring). ``n_theta``: points around each patch; ``ring_step``: profile nodes
    drawn (``thinned``); the defaults are the full resolution of ``stitchswitch preview``.
    Not thread-safe: one builder per view."""

    def __init__(self, n_theta: int = surfaces.N_THETA, ring_step: int = 1):
        if int(ring_step) < 1:
            raise InvalidInputError(f"ring_step: {ring_step!r} must be >= 1")
        self.n_theta = int(n_theta)
        self.ring_step = int(ring_step)
        self._profiles: dict = {}
        self._patches: dict = {}
        self._patch_lines: dict = {}
        self._pieces: dict = {}

    def _lookup(self, pats, material) -> list[PatchProfile]:
        keys = [(float(p.diameter_mm), float(p.fill), material) for p in pats]
        missing = sorted({k[:2] for k in keys if k not in self._profiles})
        if missing:
            if len(self._profiles) + len(missing) > PROFILE_CACHE_SIZE:
                self._profiles.clear()
                missing = sorted({k[:2] for k in keys})
            found = patch_profiles([m[0] for m in missing], [m[1] for m in missing], material)
            self._profiles.update({(*m, material): thinned(prof, self.ring_step)
                                   for m, prof in zip(missing, found)})
        return [self._profiles[k] for k in keys]

    def build(self, spec: PreviewSpec) -> Scene:
        pats, n = spec.patches, self.n_theta
        profiles = self._lookup(pats, spec.material)
        centres = np.array([p.centre_mm for p in pats], dtype=float).reshape(-1, 2)
        rims = [float(r) for r in surfaces.rim_radii_mm(centres, profiles)] if pats else []
        patches, placed = {}, []
        for p, prof, rim in zip(pats, profiles, rims):
            key = (p.id, id(prof), p.centre_mm, p.state, rim)
            part = self._patches.get(key) or PlacedPatch(
                p.id, p.state, prof, surfaces.patch_surface(prof, p.centre_mm, p.state, rim, n))
            patches[key] = part
            placed.append(part)
        pieces, built, lines = {}, [], []
        for piece in spec.pieces:
            ring = np.asarray(piece.outline_mm, dtype=float)
            bounds = (*ring.min(axis=0), *ring.max(axis=0))
            holes = tuple((p.centre_mm, rim) for p, rim in zip(pats, rims)
                          if _hole_on(bounds, p.centre_mm, rim))
            key = (piece.name, ring.tobytes(), holes)
            if key in self._pieces:
                part, line = self._pieces[key]
            else:
                pts, tris = fabric.fabric_mesh(
                    piece.name, ring, [surfaces.rim_polygon(c, r, n) for c, r in holes])
                ring3 = np.column_stack([ring, np.zeros(len(ring))])
                part = Part(piece.name, pts, tris, -1)
                line = Line(piece.name, "piece", np.vstack([ring3, ring3[:1]]))
            pieces[key] = (part, line)
            built.append(part)
            lines.append(line)
        patch_lines = {}
        eta = float(spec.material.eta)
        for p, prof in zip(pats, profiles):
            outline = None if p.outline_mm is None else np.asarray(p.outline_mm, float).tobytes()
            key = (p.id, id(prof), p.centre_mm, p.state, eta, outline)
            line = self._patch_lines.get(key) or Line(p.id, "patch", surfaces.boundary_line(
                prof, p.centre_mm, p.state, eta, p.outline_mm))
            patch_lines[key] = line
            lines.append(line)
        self._patches, self._pieces, self._patch_lines = patches, pieces, patch_lines
        return Scene(tuple(built), tuple(placed), tuple(lines))


def build_scene(spec: PreviewSpec, n_theta: int = surfaces.N_THETA) -> Scene:
    """The scene of ``spec`` built from scratch."""
    return SceneBuilder(n_theta).build(spec)
