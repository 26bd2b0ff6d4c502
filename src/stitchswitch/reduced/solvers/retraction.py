"""The polar retraction of the Newton solver: a step applied segment by segment as changes of
length and angle.

``polar(r, z, dr, dz)`` gives every segment's length l, angle phi in [-pi, 0] and their
first-order changes under the Cartesian step (dr, dz); ``point(..., alpha)`` is the profile at
step length alpha on that curve: l + alpha dl, phi + alpha dphi clipped to [-pi, 0] (z' <= 0,
the projection onto the bounds), the first segment horizontal (z'(0) = 0), r_0 = 0 and the
gauge z_{N-1} = 0. It agrees with the Cartesian update to first order, but a rotating segment
keeps its length instead of stretching along the secant (docs/model.md). Compiled, for the
Newton loop (``newton_loop``)."""
from __future__ import annotations

import math

import numpy as np
from numba import njit


@njit(cache=True)
def heights(u):
    """z (N,) from the segment drops u (N-1,), gauge z_{N-1} = 0 (``constraints.z_from_drops``)."""
    z = np.zeros(u.size + 1)
    for i in range(u.size - 1, -1, -1):
        z[i] = z[i + 1] + u[i]
    return z


@njit(cache=True)
def drops(z):
    """max(z_j - z_{j+1}, 0) per segment: the drops of an admissible profile."""
    u = np.empty(z.size - 1)
    for j in range(u.size):
        u[j] = max(z[j] - z[j + 1], 0.0)
    return u


@njit(cache=True)
def polar(r, z, d):
    """Length, angle and their first-order changes per segment for the step d (interleaved
    dofs: d[2i] = dr_i, d[2i+1] = dz_i)."""
    m = r.size - 1
    l, phi, dl, dphi = np.empty(m), np.empty(m), np.empty(m), np.empty(m)
    for i in range(m):
        vr, vz = r[i + 1] - r[i], z[i + 1] - z[i]
        if vz == 0.0 and vr > 0.0:
            # a level segment (a third of them: the held drops), without the library calls:
            # atan2(+-0, vr) = +-0 and sqrt(vr^2 + 0) = vr exactly
            li, p = vr, vz
        else:
            li = math.sqrt(vr * vr + vz * vz)   # no overflow to guard against: |v| ~ 1
            p = math.atan2(vz, vr)         # z' <= 0, so p is in [-pi, 0] up to the sign of 0
            if p > 0.0:
                p = -math.pi if p > 0.5 * math.pi else 0.0
        wr, wz = d[2 * i + 2] - d[2 * i], d[2 * i + 3] - d[2 * i + 1]
        l[i], phi[i] = li, p
        il = 1.0 / li                      # one division per segment
        dl[i] = (vr * wr + vz * wz) * il
        dphi[i] = (vr * wz - vz * wr) * (il * il)
    return l, phi, dl, dphi


@njit(cache=True)
def point(l, phi, dl, dphi, alpha):
    """(ok, r, z) at step length alpha; ok is False if a segment would reach zero length."""
    m = l.size
    r = np.zeros(m + 1)
    u = np.empty(m)
    lt = np.empty(m)
    for i in range(m):
        lt[i] = l[i] + alpha * dl[i]
        if lt[i] <= 0.0:
            return False, r, np.zeros(m + 1)
    acc = 0.0
    for i in range(m):
        p = phi[i] + alpha * dphi[i]
        p = 0.0 if i == 0 else min(max(p, -math.pi), 0.0)
        if p == 0.0:
            # a level segment without the library calls: cos(+-0) = 1 and sin(+-0) = +-0 exactly
            acc += lt[i]
            r[i + 1] = acc
            u[i] = 0.0 if i == 0 else max(-lt[i] * p, 0.0)
            continue
        acc += lt[i] * math.cos(p)
        r[i + 1] = acc
        u[i] = 0.0 if i == 0 else max(-lt[i] * math.sin(p), 0.0)
    return True, r, heights(u)
