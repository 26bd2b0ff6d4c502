"""``hardening``: the log hardening of the knit near its stretch limit (Eq. 5, sign corrected).

An extra copy of ``reduced.model.terms.hardening`` with its own weight ``w_log`` (the model's own
gamma_mm): E += (w_log / N) sum_i h(eps_theta_i), h(e) = (g - e) log(1 - e/g) + e. For a starting
material without hardening (w_log = 0) this is the paper's term switched on; otherwise it is
extra hardening on top of the starting model's. The kernel and its derivatives are the existing
term's (checked against finite differences in tests/test_energy_terms.py and again, through this
wrapper, in tests/test_effects.py).
"""
from __future__ import annotations

from types import SimpleNamespace

from stitchswitch.reduced.model.terms import hardening as _log
from stitchswitch.validation.discovery.effects.registry import Effect, EffectParameter, register_effect


def term(w_log: float, gamma_mm: float):
    """The hardening term with weight ``w_log`` and limit ``gamma_mm`` as an energy term."""
    def coefficients(grid):
        return grid.lam * grid.R[1:], gamma_mm / grid.dr_mm, w_log / grid.n_nodes

    return SimpleNamespace(__name__="effect_hardening", STENCIL=_log.STENCIL, OFFSET=_log.OFFSET,
                           coefficients=coefficients, energy=_log.energy,
                           accumulate=_log.accumulate)


EFFECT = register_effect(Effect(
    name="hardening",
    summary="log hardening of the hoop strain near its limit gamma (Eq. 5), weight w_log",
    physics="An extra sign-corrected log hardening term (w_log/N) sum h(eps_theta) with the "
            "material's gamma_mm: the knit stiffens as the circumferential strain approaches "
            "gamma. Zero weight is the starting model.",
    parameters=(EffectParameter("w_log", "1", 0.0, 5.0, probe=0.1, hidden=(3.0, 5.0)),),
    terms=lambda patch, material, v: (term(v[0], material.gamma_mm),),
))
