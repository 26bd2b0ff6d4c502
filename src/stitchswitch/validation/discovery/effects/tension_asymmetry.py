"""``tension_asymmetry``: a natural meridional curvature of the embroidered region.

Unequal top and bobbin thread tension makes a stitched layer curl. The effect gives the
meridional bending of the patch (Eq. 4) a natural curvature kappa p^2 (1/mm, weighted by p^2
like every embroidered property of the model): per hinge w (T - T_0)^2 instead of w T^2, added
as the difference (``reduced.model.terms.extra.natural_curvature``, its discretization and
derivatives). kappa > 0 curls the patch towards the pop-up dome; kappa = 0 is the starting
model.
"""
from __future__ import annotations

from stitchswitch.reduced.model.terms.extra import natural_curvature
from stitchswitch.validation.discovery.effects.registry import Effect, EffectParameter, register_effect

EFFECT = register_effect(Effect(
    name="tension_asymmetry",
    summary="natural meridional curvature kappa p^2 of the embroidered region (thread tension)",
    physics="Unequal top/bobbin thread tension makes the stitched layer curl: the bending term "
            "inside the patch gets a natural curvature kappa p^2 (1/mm), w (T - T_0)^2 instead "
            "of w T^2 per hinge. kappa > 0 curls towards the dome; kappa = 0 is the starting "
            "model.",
    parameters=(EffectParameter("kappa_per_mm", "1/mm", -0.2, 0.2, probe=0.01,
                                hidden=(-0.0075, -0.0075), signed=True),),
    terms=lambda patch, material, v: (natural_curvature.term(v[0], patch.fill),),
))
