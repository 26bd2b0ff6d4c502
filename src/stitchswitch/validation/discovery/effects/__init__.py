"""The library of candidate effects for discrepancy discovery (``validation.discovery.workflow``).

Each module is one effect: its physics, its change of the energy, rest metric or material, and
its ``register_effect`` call. ``LIBRARY`` maps names to ``Effect`` objects in the order below;
``model.configure`` / ``model.solve_effects`` add effects to the reduced model. ``gravity_sag``
is a control that is *not* registered (see its module).
"""
from stitchswitch.validation.discovery.effects.registry import (CONTROLS, LIBRARY, Effect,
                                                      EffectParameter, effect_names, get_effect,
                                                      register_control, register_effect,
                                                      resolve)
# registration order = the library's order
from stitchswitch.validation.discovery.effects import hardening  # noqa: F401, E402
from stitchswitch.validation.discovery.effects import hoop_bending  # noqa: F401, E402
from stitchswitch.validation.discovery.effects import tension_asymmetry  # noqa: F401, E402
from stitchswitch.validation.discovery.effects import prestretch_loss  # noqa: F401, E402
from stitchswitch.validation.discovery.effects import fill_exponent  # noqa: F401, E402
from stitchswitch.validation.discovery.effects import boundary_transition  # noqa: F401, E402
from stitchswitch.validation.discovery.effects import gravity_sag  # noqa: F401, E402  (a control)
from stitchswitch.validation.discovery.effects.model import configure, solve_effects

__all__ = ["LIBRARY", "CONTROLS", "Effect", "EffectParameter", "register_effect",
           "register_control", "get_effect", "resolve", "effect_names", "configure",
           "solve_effects"]
