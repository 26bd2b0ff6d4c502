"""The constraint set of the reduced model, and its bound-constrained variables.

Node coordinates (r_i, z_i), i = 0..N-1, in dR units, with

* r_0 = 0 (the pole),
* z_0 = z_1 (z'(0) = 0: the first segment is horizontal, see docs/model.md),
* z_{N-1} = 0 (the z gauge: the far fabric is the reference plane),
* z_{i+1} <= z_i for every segment (the paper's sign constraint z'(R) <= 0, pop-up state).

Writing u_j = z_j - z_{j+1} (the drop of segment j), the constraints become simple bounds
u_j >= 0 (j = 1..N-2) and u_0 = 0, and z_i = sum_{j >= i} u_j. The optimization variables
are x = (r_1..r_{N-1}, u_1..u_{N-2}), and the certificate of the solver is the projected
gradient x - P(x - grad_x E) of this bound-constrained problem.
"""
from __future__ import annotations

import numpy as np


def z_from_drops(u: np.ndarray) -> np.ndarray:
    """z (N,) from the segment drops u (N-1,), gauge z_{N-1} = 0."""
    z = np.zeros(u.size + 1)
    z[:-1] = np.cumsum(u[::-1])[::-1]
    return z


def drops_from_z(z: np.ndarray) -> np.ndarray:
    """u_j = z_j - z_{j+1} (N-1,)."""
    return z[:-1] - z[1:]


def drop_gradient(g_z: np.ndarray) -> np.ndarray:
    """dE/du_j = sum_{i <= j} dE/dz_i, from the gradient with respect to z (N,)."""
    return np.cumsum(g_z[:-1])


def projected_gradient(g_r: np.ndarray, g_z: np.ndarray, u: np.ndarray) -> np.ndarray:
    """x - P(x - grad) for x = (r_1..r_{N-1}, u_1..u_{N-2}) with bounds u >= 0."""
    g_u = drop_gradient(g_z)
    return np.concatenate([g_r[1:], np.minimum(u[1:], g_u[1:])])


def kkt_residual(g_r: np.ndarray, g_z: np.ndarray, u: np.ndarray) -> float:
    """Max-norm of the projected gradient: 0 exactly at a KKT point."""
    return float(np.max(np.abs(projected_gradient(g_r, g_z, u))))


def admissible(r: np.ndarray, z: np.ndarray, atol: float = 0.0) -> bool:
    """True if (r, z) satisfies every constraint (to ``atol`` in dR units)."""
    u = drops_from_z(z)
    return bool(r[0] == 0.0 and abs(z[-1]) <= atol and abs(u[0]) <= atol
                and np.all(u >= -atol) and np.all(r[1:] > 0))


def project(r: np.ndarray, z: np.ndarray):
    """A nearby admissible state: r_0 = 0, z_0 = z_1, monotone z with z_{N-1} = 0.

    z is projected onto non-increasing sequences (scipy's isotonic regression), then the
    pole condition and the gauge are applied; r_i is kept >= 1e-6 for i >= 1."""
    from scipy.optimize import isotonic_regression

    r = np.array(r, dtype=float)
    r[0] = 0.0
    r[1:] = np.maximum(r[1:], 1e-6)
    zz = isotonic_regression(np.asarray(z, dtype=float), increasing=False).x
    zz[0] = zz[1] = 0.5 * (zz[0] + zz[1])
    return r, zz - zz[-1]
