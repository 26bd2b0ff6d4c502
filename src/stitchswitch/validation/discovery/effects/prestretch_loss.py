"""``prestretch_loss``: the fabric was held at an effective pre-stretch below the nominal one.

eta_eff = 1 + (eta - 1) (1 - loss). The patch diameter d is still the one stitched on the hooped
fabric, so both the rest-frame radius of the embroidery (d / 2 eta_eff) and its rest metric
(1 + (eta_eff - 1) p^2) change: the material's ``eta`` is replaced. ``loss`` = 0 is the starting
model (the material is returned unchanged).
"""
from __future__ import annotations

from stitchswitch.validation.discovery.effects.registry import Effect, EffectParameter, register_effect


def material(material, values):
    (loss,) = values
    return material.replace(eta=1.0 + (material.eta - 1.0) * (1.0 - loss))


EFFECT = register_effect(Effect(
    name="prestretch_loss",
    summary="effective pre-stretch below nominal: eta_eff = 1 + (eta - 1)(1 - loss)",
    physics="The fabric relaxed or slipped in the hoop, so the embroidery was stitched at a "
            "pre-stretch eta_eff below the nominal eta: the relaxed patch radius is d / 2 eta_eff "
            "and the rest metric 1 + (eta_eff - 1) p^2. Zero loss is the starting model.",
    parameters=(EffectParameter("loss", "fraction of (eta - 1)", 0.0, 0.7, probe=0.05,
                                hidden=(0.3, 0.5)),),
    material=material,
))
