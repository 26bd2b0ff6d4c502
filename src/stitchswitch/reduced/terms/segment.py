"""Geometry shared by the terms: segment vectors, lengths and their derivatives.

Built once per evaluation by ``assembly`` and handed to every term. Segment i joins nodes i
and i+1; its local dofs are (r_i, z_i, r_{i+1}, z_{i+1})."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class Geometry:
    r: np.ndarray      # (N,) node radii, dR units
    z: np.ndarray      # (N,) node heights
    vr: np.ndarray     # (N-1,) segment vectors
    vz: np.ndarray
    l: np.ndarray      # (N-1,) segment lengths

    @property
    def unit(self) -> np.ndarray:
        """Unit segment vectors (N-1, 2)."""
        return np.stack([self.vr / self.l, self.vz / self.l], axis=1)

    def length_gradient(self) -> np.ndarray:
        """d l / d(r_i, z_i, r_{i+1}, z_{i+1}) = (-u, u), shape (N-1, 4)."""
        u = self.unit
        return np.concatenate([-u, u], axis=1)

    def length_projector(self) -> np.ndarray:
        """P = (I - u u^T) / l (N-1, 2, 2): the Hessian of l is [[P, -P], [-P, P]]."""
        u = self.unit
        P = -u[:, :, None] * u[:, None, :]
        P[:, 0, 0] += 1.0
        P[:, 1, 1] += 1.0
        return P / self.l[:, None, None]


def geometry(r: np.ndarray, z: np.ndarray) -> Geometry:
    vr, vz = r[1:] - r[:-1], z[1:] - z[:-1]
    return Geometry(r, z, vr, vz, np.hypot(vr, vz))


def segment_hessian(a: np.ndarray, b: np.ndarray, geo: Geometry) -> np.ndarray:
    """Local Hessian (n, 4, 4) of f(l) for every segment, from a = f''(l) and b = f'(l):
    a (grad l)(grad l)^T + b Hess(l) = [[K, -K], [-K, K]] with K = a u u^T + b P."""
    u = geo.unit
    K = (a - b / geo.l)[:, None, None] * (u[:, :, None] * u[:, None, :])
    K[:, 0, 0] += b / geo.l
    K[:, 1, 1] += b / geo.l
    H = np.empty((K.shape[0], 4, 4))
    H[:, :2, :2] = K
    H[:, 2:, 2:] = K
    H[:, :2, 2:] = -K
    H[:, 2:, :2] = -K
    return H
