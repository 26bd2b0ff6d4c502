"""The polar retraction's shortcut for level segments changes no number."""
import math

import numpy as np

from stitchswitch.reduced.solvers.retraction import heights, point, polar


def _polar_reference(r, z, d):
    """``polar`` with the library calls on every segment."""
    out = []
    for i in range(r.size - 1):
        vr, vz = r[i + 1] - r[i], z[i + 1] - z[i]
        li, p = math.sqrt(vr * vr + vz * vz), math.atan2(vz, vr)
        if p > 0.0:
            p = -math.pi if p > 0.5 * math.pi else 0.0
        wr, wz = d[2 * i + 2] - d[2 * i], d[2 * i + 3] - d[2 * i + 1]
        il = 1.0 / li
        out.append((li, p, (vr * wr + vz * wz) * il, (vr * wz - vz * wr) * (il * il)))
    return tuple(np.array(x) for x in zip(*out))


def _point_reference(l, phi, dl, dphi, alpha):
    lt = l + alpha * dl
    r, u, acc = np.zeros(l.size + 1), np.empty(l.size), 0.0
    for i in range(l.size):
        p = phi[i] + alpha * dphi[i]
        p = 0.0 if i == 0 else min(max(p, -math.pi), 0.0)
        acc += lt[i] * math.cos(p)
        r[i + 1] = acc
        u[i] = 0.0 if i == 0 else max(-lt[i] * math.sin(p), 0.0)
    return r, heights(u)


def test_level_segments_give_the_library_calls_numbers_bit_for_bit():
    rng = np.random.default_rng(3)
    n = 120
    r = np.cumsum(rng.uniform(0.5, 1.5, n))
    r[0] = 0.0
    z = np.sort(rng.uniform(0.0, 10.0, n))[::-1].copy()
    z[:2] = z[1]
    z[60:] = 0.0                                   # a level stretch (held drops)
    z[30:40] = z[30]                               # and a raised one
    d = 0.05 * rng.standard_normal(2 * n)
    d[121:] = 0.0                                  # the level stretch rotates as one group
    d[1::2][30:40] = d[61]
    got, ref = polar(r, z, d), _polar_reference(r, z, d)
    for a, b in zip(got, ref):
        assert a.tobytes() == b.tobytes()
    for alpha in (1.0, 0.5, 1e-3):
        ok, r_new, z_new = point(*got, alpha)
        r_ref, z_ref = _point_reference(*ref, alpha)
        assert ok and r_new.tobytes() == r_ref.tobytes() and z_new.tobytes() == z_ref.tobytes()
    assert np.count_nonzero(np.diff(z) == 0.0) > 60      # the shortcut was taken
