"""Plane vector arithmetic whose results do not depend on the machine.

``np.linalg.norm`` of one vector, ``np.dot`` and ``@`` call the BLAS library, whose kernels
differ between processors (OpenBLAS picks one per CPU model; some contract a multiply and an
add into one rounding): the last bit of a length then differs from one machine to the next,
and a stitch count taken by rounding a length up (``ceil(length / step)``) can change. The
stitch paths, and so the machine files, are built with these helpers instead: Python's
``math.hypot`` and elementwise products and sums, each rounded the same way everywhere, so the
same design gives byte-identical files on every machine.
"""
from __future__ import annotations

import math

import numpy as np

__all__ = ["length", "dot", "transform"]


def length(v) -> float:
    """The Euclidean length of the plane vector ``v``."""
    return math.hypot(float(v[0]), float(v[1]))


def dot(u, v) -> float:
    """The scalar product of the plane vectors ``u`` and ``v``."""
    return float(u[0]) * float(v[0]) + float(u[1]) * float(v[1])


def transform(points, matrix) -> np.ndarray:
    """``points @ matrix`` for (n, 2) points and a 2 x 2 matrix, without BLAS."""
    p = np.asarray(points, dtype=float)
    m = np.asarray(matrix, dtype=float)
    x, y = p[..., 0], p[..., 1]
    return np.stack([x * m[0, 0] + y * m[1, 0], x * m[0, 1] + y * m[1, 1]], axis=-1)
