"""``hardening``: the log hardening of the knit near its stretch limit (Eq. 5, sign corrected).

An extra copy of the model's hardening term with its own weight ``w_log`` and the material's
gamma_mm (``reduced.model.terms.hardening.with_weight``): E += (w_log / N) sum_i h(eps_theta_i),
h(e) = (g - e) log(1 - e/g) + e. For a starting material without hardening (w_log = 0) this is
the paper's term switched on; otherwise it is extra hardening on top of the starting model's.
"""
from __future__ import annotations

from stitchswitch.reduced.model.terms import hardening
from stitchswitch.validation.discovery.effects.registry import Effect, EffectParameter, register_effect

EFFECT = register_effect(Effect(
    name="hardening",
    summary="log hardening of the hoop strain near its limit gamma (Eq. 5), weight w_log",
    physics="An extra sign-corrected log hardening term (w_log/N) sum h(eps_theta) with the "
            "material's gamma_mm: the knit stiffens as the circumferential strain approaches "
            "gamma. Zero weight is the starting model.",
    parameters=(EffectParameter("w_log", "1", 0.0, 5.0, probe=0.1, hidden=(3.0, 5.0)),),
    terms=lambda patch, material, v: (hardening.with_weight(v[0], material.gamma_mm),),
))
