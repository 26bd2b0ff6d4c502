"""The shell's moduli in the embroidered disc and in the bare knit, mapped from the reduced
model's calibrated ``Material`` (docs/fem-reference.md, "Parameter map").

The fill-mixture law is the reduced model's (``discretization.fill_mixture``). Per region, with
lambda the natural metric, k_r, k_theta, w_b the mixed coefficients and c the compressive ratio:

    A_s = 2 k_r lambda,  A_t = 2 k_theta / lambda     membrane stiffness per natural area
    C = nu sqrt(A_s A_t)                              Poisson coupling
    D = w_b dR_ref^2 / 4   (or sqrt(A_s A_t) t^2 / 12 from a thickness)   bending rigidity

chosen so that, with nu = 0 and the shell's other switches off, the shell's tensile membrane and
meridional bending energies at the natural state equal the reduced model's continuum energy
(``docs/model.md``: k_r lambda (l - lambda)^2 S, k_theta (r - lambda S)^2 / (lambda S),
w_b dR_ref^2 r l kappa^2 / 8 per unit rest radius). The compressive ratio c (c_emb, c_fab and the
numerical floor), the jamming stretch and stiffness, and the hoop hardening (w_log, gamma_mm) are
the material's. The natural curvature acts in the embroidered disc only.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from stitchswitch.fem_reference.revolution.params import ShellParams
from stitchswitch.reduced.model.discretization import BENDING_REFERENCE_MM, fill_mixture
from stitchswitch.reduced.model.params import Material, Patch


@dataclass(frozen=True)
class Moduli:
    """One region's constitutive constants (see the module docstring)."""

    lam: float
    a_s: float
    a_t: float
    coupling: float
    bending: float
    compression: float
    jam: float
    c_jam: float
    w_log: float
    gamma_mm: float
    kappa0_per_mm: float
    relaxed: bool          # full tension-field relaxation (bare knit with the switch on)
    hoop_bending: bool
    nu: float


def region_moduli(patch: Patch, material: Material, params: ShellParams) -> tuple[Moduli, Moduli]:
    """(inside, outside): the embroidered disc and the bare knit."""
    mix = fill_mixture(np.array([True, False]), patch.fill, material)
    out = []
    for k, inside in enumerate((True, False)):
        lam = float(mix.lam[k])
        a_s, a_t = 2.0 * float(mix.k_r[k]) * lam, 2.0 * float(mix.k_theta[k]) / lam
        if params.thickness_mm is None:
            d = float(mix.w_b[k]) * BENDING_REFERENCE_MM ** 2 / 4.0
        else:
            d = float(np.sqrt(a_s * a_t)) * params.thickness_mm ** 2 / 12.0
        out.append(Moduli(
            lam=lam, a_s=a_s, a_t=a_t, coupling=params.nu * float(np.sqrt(a_s * a_t)), bending=d,
            compression=float(mix.compression[k]), jam=material.jam, c_jam=material.c_jam,
            w_log=material.w_log, gamma_mm=material.gamma_mm,
            kappa0_per_mm=params.kappa0_per_mm if inside else 0.0,
            relaxed=params.relaxed_membrane and not inside, hoop_bending=params.hoop_bending,
            nu=params.nu))
    return out[0], out[1]


def force_scale_n_per_model(material: Material, params: ShellParams) -> float:
    """Newtons per model force unit: the bare knit's tensile stiffness Y (N/m) over its model
    modulus A_s = 2 k_r_fab, times 2 pi (the model drops the azimuthal integral) and 1e-3 (mm^2
    of energy per mm of displacement: F = dE/dw)."""
    return 2.0 * np.pi * 1e-3 * params.knit_stiffness_n_per_m / (2.0 * material.k_r_fab)
