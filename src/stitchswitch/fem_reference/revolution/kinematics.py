"""Kinematics of the axisymmetric Kirchhoff-Love shell: strains and curvatures of a meridian.

The meridian is (r(S), z(S)) over the rest radius S of the relaxed fabric (mm); the natural
(stress-free) metric of the layer is lambda(S) times the rest metric (lambda > 1 in the
embroidered disc, 1 in the bare knit). With l = |(r', z')|:

    eps_s = l / lambda - 1                  meridional (Biot) strain
    eps_t = r / (lambda S) - 1              hoop strain
    k_s = (z' r'' - r' z'') / l^3           meridional curvature
    k_t = -z' / (l r)                       hoop curvature sin(phi) / r

with both curvatures positive on a pop-up dome (z decreasing outward). These are the exact
strains of a shell of revolution (no small-slope or small-strain assumption in the geometry);
the shell is shear-rigid (Kirchhoff-Love), so the tangent angle phi is continuous, but l, and so
eps_s, may jump across a material interface.
"""
from __future__ import annotations

import numpy as np

from stitchswitch.fem_reference.revolution.jet import Jet

#: Order of the pointwise fields.
FIELDS = ("r", "dr", "dz", "d2r", "d2z")


def strains(q: np.ndarray, S: np.ndarray, lam: np.ndarray, derivatives: bool = True):
    """Jets (eps_s, eps_t, k_s, k_t) at the points of ``q`` (m >= 5, P): r, r', z', r'', z''
    first (the jets are in all m fields)."""
    r, rp, zp, rpp, zpp = (Jet.variable(q, k, derivatives) for k in range(5))
    l = (rp * rp + zp * zp).sqrt()
    eps_s = l / lam - 1.0
    eps_t = r / (lam * S) - 1.0
    k_s = (zp * rpp - rp * zpp) * l.power(-3.0)
    k_t = -(zp * (l * r).power(-1.0))
    return eps_s, eps_t, k_s, k_t
