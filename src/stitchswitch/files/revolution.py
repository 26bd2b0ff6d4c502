"""Surfaces of revolution from 1D profiles, and mesh files through meshio.

A profile (r_i, z_i) revolved about the z axis gives a triangulated surface: ``n_theta``
copies of the profile around the circle, the pole collapsed to one point. ``write_mesh``
writes VTU, VTK, PLY, OBJ, STL or OFF (``MESH_EXTENSIONS``) atomically: meshio writes a
temporary file next to the target (``files.tempnames``); the time meshio stamps into PLY and
OBJ headers is removed, so that the same mesh gives the same bytes.
"""
from __future__ import annotations

import os
import re

import numpy as np

from stitchswitch.errors import InvalidInputError
from stitchswitch.files.atomic import atomic_write_bytes
from stitchswitch.files.extensions import check_extension
from stitchswitch.files.tempnames import remove_stale, temp_path


def surface_of_revolution(r: np.ndarray, z: np.ndarray, n_theta: int = 64):
    """(points (M, 3), triangles (K, 3)) of the profile revolved about the z axis.

    Node 0 must be on the axis (r_0 = 0); it becomes a single pole point."""
    r, z = np.asarray(r, float), np.asarray(z, float)
    if r.ndim != 1 or r.shape != z.shape or r.size < 2:
        raise InvalidInputError("profile: r and z must be 1D arrays of the same length (>= 2)")
    if abs(r[0]) > 1e-12:
        raise InvalidInputError(f"profile: r[0] = {r[0]:g} must be 0 (the pole)")
    if n_theta < 3:
        raise InvalidInputError(f"n_theta: {n_theta} must be >= 3")
    t = 2 * np.pi * np.arange(n_theta) / n_theta
    ring_r, ring_z = r[1:], z[1:]
    pts = np.column_stack([np.outer(ring_r, np.cos(t)).ravel(), np.outer(ring_r, np.sin(t)).ravel(),
                           np.repeat(ring_z, n_theta)])
    points = np.vstack([[0.0, 0.0, z[0]], pts])
    idx = lambda i, j: 1 + i * n_theta + (j % n_theta)            # noqa: E731
    j = np.arange(n_theta)
    tris = [np.column_stack([np.zeros(n_theta, int), idx(0, j), idx(0, j + 1)])]
    for i in range(ring_r.size - 1):
        tris.append(np.column_stack([idx(i, j), idx(i + 1, j), idx(i + 1, j + 1)]))
        tris.append(np.column_stack([idx(i, j), idx(i + 1, j + 1), idx(i, j + 1)]))
    return points, np.vstack(tris)


#: The mesh formats ``write_mesh`` writes (meshio's writers for these extensions).
MESH_EXTENSIONS = (".vtu", ".vtk", ".ply", ".obj", ".stl", ".off")


def write_mesh(path, points, triangles, point_data: dict | None = None) -> None:
    """Write a triangle mesh with meshio (format from the extension, one of
    ``MESH_EXTENSIONS``), atomically."""
    import meshio

    path = os.fspath(path)
    ext = os.path.splitext(path)[1].lower()
    if not ext:
        raise InvalidInputError(f"mesh file {path!r}: no extension to choose the format "
                                f"({', '.join(MESH_EXTENSIONS)})")
    check_extension(path, MESH_EXTENSIONS, "mesh file")
    (fmt,) = meshio.extension_to_filetypes[ext][:1]
    # 32-bit connectivity: PLY has no 64-bit integers (meshio would cast and print a warning)
    mesh = meshio.Mesh(points, [("triangle", np.asarray(triangles, dtype=np.int32))],
                       point_data=point_data or {})
    remove_stale(path)
    tmp = temp_path(path)
    try:
        try:
            meshio.write(os.fspath(tmp), mesh, file_format=fmt)
        except (meshio.WriteError, KeyError, ValueError) as exc:
            raise InvalidInputError(f"mesh file {path!r}: {exc}") from None
        with open(tmp, "rb") as f:
            data = f.read()
    finally:
        if os.path.exists(tmp):
            os.remove(tmp)
    atomic_write_bytes(path, _MESHIO_STAMP.sub(rb"\1", data, count=1))


#: The time meshio writes into the header comment of PLY and OBJ files ("Created by meshio
#: v5.3.5, 2026-01-01T12:00:00.000000"): removed, so that the same mesh gives the same bytes.
_MESHIO_STAMP = re.compile(rb"(Created by meshio v[^,\r\n]*), \d{4}-\d\d-\d\dT[\d:.]+")
