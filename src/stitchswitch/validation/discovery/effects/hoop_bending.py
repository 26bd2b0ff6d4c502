"""``hoop_bending``: bending of the parallels (hoop curvature sin(phi)/r), which Eq. 4 drops.

The shell reference's density has the bending term B r l (kappa_s^2 + H kappa_t^2); the reduced
model keeps only the meridional curvature kappa_s. The effect adds the hoop part with weight H
(``reduced.model.terms.extra.hoop_bending``, its discretization and derivatives): H = 1 is an isotropic
shell with the model's bending stiffness, H = 0 the starting model.
"""
from __future__ import annotations

from stitchswitch.reduced.model.terms.extra import hoop_bending
from stitchswitch.validation.discovery.effects.registry import Effect, EffectParameter, register_effect

EFFECT = register_effect(Effect(
    name="hoop_bending",
    summary="bending of the parallels (hoop curvature sin(phi)/r) with weight H",
    physics="The reduced model keeps only meridional bending (Eq. 4); a shell also resists "
            "bending of its parallels, kappa_t = sin(phi)/r. Added per segment as "
            "H w_b dz^2 / (8 l rbar), the discrete form of the shell reference's hoop term; "
            "H = 1 is an isotropic shell, H = 0 the starting model.",
    parameters=(EffectParameter("H", "1", 0.0, 50.0, probe=1.0, hidden=(0.5, 1.0)),),
    terms=lambda patch, material, v: (hoop_bending.term(v[0]),),
))
