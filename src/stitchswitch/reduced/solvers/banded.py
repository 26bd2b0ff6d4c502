"""Banded linear algebra for the Newton solver: restriction of the Hessian to the reduced
variables of an active set, and a positive-definiteness-checking Cholesky solve."""
from __future__ import annotations

import numpy as np
from numba import njit
from scipy.linalg import eig_banded
from scipy.linalg.lapack import dpbtrf, dpbtrs

from stitchswitch.errors import StitchSwitchError


@njit(cache=True)
def restrict(hb, dof_map, n_red):
    """P^T H P in lower band storage, for H given as a lower band ``hb`` (global dofs) and P
    the 0/1 matrix that maps reduced variable ``dof_map[a]`` to global dof a (-1: fixed).

    Several global dofs may share one reduced variable (merged z groups): their coupling then
    counts twice on the diagonal. The bandwidth of the result is found first."""
    kmax, n = hb.shape
    bw = 0
    for j in range(n):
        J = dof_map[j]
        if J < 0:
            continue
        for k in range(kmax):
            if j + k < n and dof_map[j + k] >= 0:
                bw = max(bw, abs(dof_map[j + k] - J))
    ab = np.zeros((bw + 1, n_red))
    for j in range(n):
        J = dof_map[j]
        if J < 0:
            continue
        for k in range(kmax):
            if j + k >= n:
                break
            I = dof_map[j + k]
            if I < 0:
                continue
            v = hb[k, j]
            if I == J:
                ab[0, I] += v if k == 0 else 2.0 * v
            elif I > J:
                ab[I - J, J] += v
            else:
                ab[J - I, I] += v
    return ab


def cholesky(ab: np.ndarray, shift: float = 0.0):
    """Lower banded Cholesky factor of ab + shift I (LAPACK dpbtrf), or None if that is not
    positive definite."""
    m = ab.copy()
    m[0] += shift
    factor, info = dpbtrf(m, lower=1)
    return factor if info == 0 else None


def solve(factor: np.ndarray, rhs: np.ndarray) -> np.ndarray:
    """Solve with a factor from ``cholesky`` (LAPACK dpbtrs)."""
    x, info = dpbtrs(factor, rhs, lower=1)
    if info != 0:
        raise StitchSwitchError(f"banded solve: LAPACK dpbtrs failed with info={info}")
    return x


def lowest_mode(ab: np.ndarray) -> tuple[float, np.ndarray]:
    """Smallest eigenvalue and its unit eigenvector of a symmetric lower-banded matrix."""
    w, v = eig_banded(ab, lower=True, select="i", select_range=(0, 0), check_finite=False)
    return float(w[0]), v[:, 0]
