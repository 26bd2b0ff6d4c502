"""Constitutive laws of the shell: the membrane (taut, relaxed, with a compressive residual),
jamming, hoop hardening and Kirchhoff-Love bending, as energies per unit rest radius S.

Membrane (per natural area lambda^2 S dS), strains a = eps_s, b = eps_t, stresses
n_s = A_s a + C b and n_t = A_t b + C a:

* taut: W_T = (A_s a^2 + A_t b^2 + 2 C a b) / 2;
* relaxed (Pipkin's tension-field energy; its quasiconvex envelope for this quadratic W_T):
  W_T where n_s > 0 and n_t > 0; (A_s - C^2/A_t) a^2 / 2 where a > 0 and n_t <= 0 (hoop
  wrinkled); (A_t - C^2/A_s) b^2 / 2 where b > 0 and n_s <= 0 (meridian wrinkled); 0 where
  slack both ways. C1, convex;
* meridian-relaxed: W_T where n_s >= 0, else (A_t - C^2/A_s) b^2 / 2: the meridian may
  wrinkle, the hoop carries compression (the reduced model's tension-only meridional term).

A region's membrane energy is (1 - c) W_relax + c W_c, c its compressive ratio and W_c the
taut energy with the meridional a^2 replaced, for a < 0, by the reduced model's psi(1 + a) =
2 (a - ln(1 + a)) (same stiffness at a = 0, +inf as the stretch goes to 0): the stitched disc
and, with ``relaxed_membrane`` off, the bare knit use the meridian-relaxed W_relax (so
meridional compression has the stiffness c A_s, as in the reduced model); the bare knit with the
switch on uses Pipkin's. With nu = 0 the taut, compressed-meridian and jammed parts equal the
reduced model's continuum energy (``moduli``).

Jamming: c_jam A_s (jam - 1 - a)_+^2 / 2 per natural area. Hoop hardening (the material's
sign-corrected Eq. 5, a function of the hoop displacement Delta = r - lambda S in mm):
w_log h(Delta) per dS, only its tension part in the relaxed knit. Bending per natural area:
D/2 [(k_s - k0)^2 + (k_t - k0)^2 + 2 nu (k_s - k0)(k_t - k0)], hoop terms only with
``hoop_bending``.
"""
from __future__ import annotations

import numpy as np

from stitchswitch.fem_reference.revolution.jet import Jet
from stitchswitch.fem_reference.revolution.moduli import Moduli
from stitchswitch.reduced.model.terms.hardening import h as hardening


def _taut(a: Jet, b: Jet, m: Moduli) -> Jet:
    return (a.square() * m.a_s + b.square() * m.a_t) * 0.5 + a * b * m.coupling


def _compressible(a: Jet) -> Jet:
    """a^2 for a >= 0, the reduced model's psi(1 + a) = 2 (a - ln(1 + a)) for a < 0: the same
    curvature 2 at a = 0, and +inf as the stretch 1 + a goes to 0 (no fold of zero length)."""
    t = 1.0 + a.v
    neg = a.v < 0.0
    ts = np.where(t > 0.0, t, np.nan)
    with np.errstate(invalid="ignore", divide="ignore"):
        v = np.where(neg, np.where(t > 0.0, 2.0 * (a.v - np.log(ts)), np.inf), a.v * a.v)
        d1 = np.where(neg, 2.0 * (1.0 - 1.0 / ts), 2.0 * a.v)
        d2 = np.where(neg, 2.0 / (ts * ts), 2.0)
    return a.chain(v, d1, d2)


def _residual(a: Jet, b: Jet, m: Moduli) -> Jet:
    """The taut energy with the meridional a^2 replaced by ``_compressible``: convex for
    |nu| < 1, since its curvature in a is at least A_s."""
    return (_compressible(a) * m.a_s + b.square() * m.a_t) * 0.5 + a * b * m.coupling


def _relaxed(a: Jet, b: Jet, m: Moduli, full: bool) -> Jet:
    ns = m.a_s * a.v + m.coupling * b.v
    nt = m.a_t * b.v + m.coupling * a.v
    taut = _taut(a, b, m)
    hoop_only = b.square() * (0.5 * (m.a_t - m.coupling ** 2 / m.a_s))
    if not full:
        return Jet.where(ns >= 0.0, taut, hoop_only)
    meridian_only = a.square() * (0.5 * (m.a_s - m.coupling ** 2 / m.a_t))
    out = Jet.where((ns > 0.0) & (nt > 0.0), taut, Jet.zero_like(taut))
    out = Jet.where((a.v > 0.0) & (nt <= 0.0), meridian_only, out)
    return Jet.where((b.v > 0.0) & (ns <= 0.0), hoop_only, out)


def membrane(a: Jet, b: Jet, m: Moduli) -> Jet:
    """Membrane energy per natural area, jamming included."""
    c = m.compression
    w = _relaxed(a, b, m, m.relaxed) * (1.0 - c) + _residual(a, b, m) * c
    return w + (-(a + (1.0 - m.jam))).positive_square() * (0.5 * m.c_jam * m.a_s)


def hoop_hardening(b: Jet, S: np.ndarray, m: Moduli) -> Jet:
    """w_log h(lambda S b) per unit rest radius (the hoop displacement in mm)."""
    delta = b * (m.lam * S)
    v, d1, d2 = hardening(delta.v, m.gamma_mm)
    hj = delta.chain(v, d1, d2)
    if m.relaxed:
        on = delta.v > 0.0
        hj = Jet.where(on, hj, Jet.zero_like(hj)) * (1.0 - m.compression) + hj * m.compression
    return hj * m.w_log


def bending(k_s: Jet, k_t: Jet, m: Moduli) -> Jet:
    """Kirchhoff-Love bending energy per natural area."""
    ds = k_s - m.kappa0_per_mm
    w = ds.square()
    if m.hoop_bending:
        dt = k_t - m.kappa0_per_mm
        w = w + dt.square() + ds * dt * (2.0 * m.nu)
    return w * (0.5 * m.bending)
