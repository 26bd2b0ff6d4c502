"""Kernels shared by the terms: scattering local gradients and Hessians into the global
arrays, and the Hessian of a segment's length. Global dofs are interleaved node by node
(dof 2i = r_i, dof 2i+1 = z_i); the Hessian is kept in LAPACK lower band storage
``hb[k, j] = H[j + k, j]`` with k = 0..5 (every term couples at most three consecutive nodes)."""
from __future__ import annotations

import math

import numpy as np
from numba import njit

#: Half-bandwidth of the Hessian in interleaved dofs (three-node stencils).
BANDWIDTH = 5


@njit(cache=True)
def segment(r, z, i):
    """Vector (vr, vz) and length of segment i (nodes i, i+1)."""
    vr, vz = r[i + 1] - r[i], z[i + 1] - z[i]
    return vr, vz, math.sqrt(vr * vr + vz * vz)


@njit(cache=True)
def segment_lengths(r, z):
    """The length of every segment (``segment``'s numbers)."""
    lengths = np.empty(r.size - 1)
    for i in range(r.size - 1):
        lengths[i] = segment(r, z, i)[2]
    return lengths


@njit(cache=True)
def add_local(grad, hb, first, g, H, m, want_h):
    """grad[first + p] += g[p]; H (m x m, symmetric) into the band at dofs first..first+m-1."""
    for p in range(m):
        grad[first + p] += g[p]
    if want_h:
        for p in range(m):
            for q in range(p + 1):
                hb[p - q, first + q] += H[p, q]


@njit(cache=True)
def add_length_hessian(H, off, k, ur, uz, l):
    """H += k Hess l = k [[P, -P], [-P, P]] (lower triangle) at local dofs off..off+3, for a
    segment of length l and unit vector u, P = (I - u u^T) / l."""
    prr, prz, pzz = k * (1.0 - ur * ur) / l, -k * ur * uz / l, k * (1.0 - uz * uz) / l
    H[off, off] += prr
    H[off + 1, off] += prz
    H[off + 1, off + 1] += pzz
    H[off + 2, off] -= prr
    H[off + 2, off + 1] -= prz
    H[off + 3, off] -= prz
    H[off + 3, off + 1] -= pzz
    H[off + 2, off + 2] += prr
    H[off + 3, off + 2] += prz
    H[off + 3, off + 3] += pzz


@njit(cache=True)
def add_segment(grad, hb, i, dEdl, d2Edl2, vr, vz, l, want_h):
    """Scatter f(l) of segment i (nodes i, i+1): gradient dEdl (-u, u) and Hessian
    [[K, -K], [-K, K]] with K = f'' u u^T + (f' / l) (I - u u^T)."""
    ur, uz = vr / l, vz / l
    a = 2 * i
    grad[a] -= dEdl * ur
    grad[a + 1] -= dEdl * uz
    grad[a + 2] += dEdl * ur
    grad[a + 3] += dEdl * uz
    if want_h:
        t = dEdl / l
        krr = (d2Edl2 - t) * ur * ur + t
        krz = (d2Edl2 - t) * ur * uz
        kzz = (d2Edl2 - t) * uz * uz + t
        # lower triangle of [[K, -K], [-K, K]] in local dofs (r_i, z_i, r_i+1, z_i+1)
        hb[0, a] += krr
        hb[1, a] += krz
        hb[0, a + 1] += kzz
        hb[2, a] -= krr
        hb[3, a] -= krz
        hb[1, a + 1] -= krz
        hb[2, a + 1] -= kzz
        hb[0, a + 2] += krr
        hb[1, a + 2] += krz
        hb[0, a + 3] += kzz


#: Placeholders for evaluations without a gradient or a Hessian (same array types as the real
#: ones, so the kernels are compiled once); the kernels never write into them.
NO_GRADIENT = np.zeros(0)
NO_HESSIAN = np.zeros((BANDWIDTH + 1, 0))
