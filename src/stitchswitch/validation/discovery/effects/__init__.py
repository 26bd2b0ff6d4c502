"""The library of candidate effects for discrepancy discovery (``validation.discovery.workflow``).

Each module is one effect: its physics, its change of the energy, rest metric or material, and
its ``register_effect`` call. ``LIBRARY`` maps names to ``Effect`` objects in the order below;
``model.configure`` / ``model.solve_effects`` add effects to the reduced model. ``gravity_sag``
is a control that is *not* registered (see its module).
"""
# registration order = the library's order
from stitchswitch.validation.discovery.effects import (
                                                      boundary_transition,  # noqa: F401, E402
                                                      fill_exponent,  # noqa: F401, E402
                                                      gravity_sag,  # noqa: F401, E402  (a control)
                                                      hardening,  # noqa: F401, E402
                                                      hoop_bending,  # noqa: F401, E402
                                                      prestretch_loss,  # noqa: F401, E402
                                                      tension_asymmetry,  # noqa: F401, E402
)
from stitchswitch.validation.discovery.effects.model import configure, solve_effects
from stitchswitch.validation.discovery.effects.registry import (
                                                      CONTROLS,
                                                      LIBRARY,
                                                      Effect,
                                                      EffectParameter,
                                                      effect_names,
                                                      get_effect,
                                                      register_control,
                                                      register_effect,
                                                      resolve,
)

__all__ = ["LIBRARY", "CONTROLS", "Effect", "EffectParameter", "register_effect",
           "register_control", "get_effect", "resolve", "effect_names", "configure",
           "solve_effects"]
