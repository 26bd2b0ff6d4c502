"""Mesh export of a scene through meshio: VTU, PLY or OBJ, chosen by the extension, atomic.

The exported mesh is ``Scene.merged()``: every piece and patch surface as triangles in garment
mm. VTU and PLY carry the point data ``height_mm`` and ``patch_index`` (-1 on the flat fabric);
OBJ has no place for them and carries the geometry only.
"""
from __future__ import annotations

from stitchswitch.errors import InvalidInputError
from stitchswitch.files.extensions import check_extension
from stitchswitch.files.revolution import write_mesh

MESH_EXTENSIONS = (".vtu", ".ply", ".obj")


def check_mesh_path(path) -> str:
    return check_extension(path, MESH_EXTENSIONS, "mesh file")


def write_scene_mesh(path, scene) -> int:
    """Write the merged mesh; returns its point count."""
    ext = check_mesh_path(path)
    points, tris, data = scene.merged()
    if not len(tris):
        raise InvalidInputError("mesh: the scene is empty (no pieces and no patches)")
    write_mesh(path, points, tris, None if ext == ".obj" else data)
    return len(points)
