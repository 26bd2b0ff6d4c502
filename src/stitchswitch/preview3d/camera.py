"""Cameras of the three views, fitted to the scene, and the world-to-pixel map (numpy only).

Every view uses a parallel projection: ``parallel_scale`` is half the image height in mm, so a
length reads the same anywhere in the image. ``top`` looks down -z with +y up (the pattern as
drawn); ``side`` looks along +y (from the front, -y) with +z up, showing heights; ``iso`` looks
from (+x, -y, +z) with +z up. The scene's points, projected on the image plane, are fitted into
the left ``usable`` fraction of the width (the rest is kept for the colour bar or legend).

Framing (``frame_points``): by default the camera is fitted to the patches (each patch's surface
out to its rim), so that a dome of a few centimetres on a garment panel fills the image instead
of a corner of it; ``piece`` frames one whole piece with its patches, ``patch`` one patch; a
design without patches is framed whole.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from stitchswitch.errors import InvalidInputError

#: view -> (direction from the focal point to the camera, view-up)
VIEWS = {
    "iso": ((1.0, -1.0, 1.0), (0.0, 0.0, 1.0)),
    "top": ((0.0, 0.0, 1.0), (0.0, 1.0, 0.0)),
    "side": ((0.0, -1.0, 0.0), (0.0, 0.0, 1.0)),
}


@dataclass(frozen=True)
class Camera:
    position: tuple[float, float, float]
    focal_point: tuple[float, float, float]
    view_up: tuple[float, float, float]
    parallel_scale: float

    def axes(self):
        """(right, up) unit vectors of the image plane, in world coordinates."""
        v = np.subtract(self.focal_point, self.position)
        v /= np.linalg.norm(v)
        up = np.asarray(self.view_up, dtype=float)
        up = up - up.dot(v) * v
        up /= np.linalg.norm(up)
        return np.cross(v, up), up


def check_view(view: str) -> str:
    if view not in VIEWS:
        raise InvalidInputError(f"view: {view!r} is not one of " + ", ".join(VIEWS))
    return view


def frame_points(scene, piece: str | None = None, patch: str | None = None) -> np.ndarray:
    """The points (n, 3) the camera is fitted to: the patches' surfaces by default, the piece
    named ``piece`` (its mesh, outline and patches), or the patch ``patch``."""
    if piece is not None and patch is not None:
        raise InvalidInputError("give --piece or --patch, not both")
    if patch is not None:
        found = [p for p in scene.patches if p.id == patch]
        if not found:
            raise InvalidInputError(f"--patch: no patch {patch!r} in the design"
                                    + _choices(p.id for p in scene.patches))
        return found[0].surface.points
    if piece is not None:
        parts = [p.points for p in scene.pieces if p.name == piece]
        if not parts:
            raise InvalidInputError(f"--piece: no piece {piece!r} in the design"
                                    + _choices(p.name for p in scene.pieces))
        lines = [ln.points for ln in scene.lines if ln.kind == "piece" and ln.name == piece]
        return np.vstack(parts + lines)
    if scene.patches:
        return np.vstack([p.surface.points for p in scene.patches])
    return scene.all_points()


def _choices(names) -> str:
    names = list(names)
    if not names:
        return " (it has none)"
    shown = ", ".join(names[:8]) + (", ..." if len(names) > 8 else "")
    return f"; it has {shown}"


def fit_camera(points, view: str, size: tuple[int, int], usable: float = 1.0,
               margin: float = 1.05) -> Camera:
    """The camera of ``view`` that shows all ``points`` (n, 3), centred in the usable width."""
    direction, up = VIEWS[check_view(view)]
    pts = np.asarray(points, dtype=float).reshape(-1, 3)
    if not len(pts):
        pts = np.zeros((1, 3))
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    centre = (lo + hi) / 2.0
    d = np.asarray(direction) / np.linalg.norm(direction)
    diag = max(float(np.linalg.norm(hi - lo)), 1.0)
    probe = Camera(tuple(centre + d * 2 * diag), tuple(centre), up, 1.0)
    right, upv = probe.axes()
    u, v = (pts - centre) @ right, (pts - centre) @ upv
    # centre the projected extent, not the bounding box
    centre = centre + right * (u.max() + u.min()) / 2 + upv * (v.max() + v.min()) / 2
    half_w, half_h = (u.max() - u.min()) / 2, (v.max() - v.min()) / 2
    w, h = size
    scale = margin * max(half_h, half_w * h / (w * usable), 1e-3)
    # shift the focal point right so the scene's centre falls at usable/2 of the width
    shift = (0.5 - usable / 2.0) * w * scale / (h / 2.0)
    focal = centre + right * shift
    return Camera(tuple(focal + d * 2 * diag), tuple(focal), up, float(scale))


def world_to_pixel(camera: Camera, size: tuple[int, int], xyz) -> np.ndarray:
    """(column, row) pixel coordinates, row 0 at the top, of world points (n, 3)."""
    w, h = size
    right, up = camera.axes()
    rel = np.atleast_2d(np.asarray(xyz, dtype=float)) - np.asarray(camera.focal_point)
    k = (h / 2.0) / camera.parallel_scale
    return np.column_stack([w / 2.0 + (rel @ right) * k, h / 2.0 - (rel @ up) * k])
