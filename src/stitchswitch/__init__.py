"""stitchswitch: design and fabrication of bistable embroidered textiles.

Internal length unit: millimetres, measured in the *rest frame* of the relaxed fabric
unless a name says otherwise (``diameter_mm`` is measured on the pre-stretched fabric,
as in the paper). The reduced model works internally in units of the node spacing dR
(see ``docs/model.md``); everything it returns is converted back to mm.
"""
from stitchswitch.errors import InvalidInputError, StitchSwitchError
from stitchswitch.reduced.model.params import DEFAULT_MATERIAL, Material, Patch

__version__ = "0.1.0"
__all__ = [
    "StitchSwitchError", "InvalidInputError", "Material", "Patch", "DEFAULT_MATERIAL",
    "solve", "Solution", "keypoints", "Keypoints", "__version__",
]

# The solver pulls in the compiled (numba) energy kernels, about 0.6 s of import time; it is
# imported on first use, so that commands that never solve (check, fabricate, ...) start fast.
_LAZY = {"solve": "stitchswitch.reduced.solvers.solve", "Solution": "stitchswitch.reduced.solvers.solve",
         "keypoints": "stitchswitch.reduced.model.keypoints", "Keypoints": "stitchswitch.reduced.model.keypoints"}


def __getattr__(name):
    if name in _LAZY:
        from importlib import import_module

        value = getattr(import_module(_LAZY[name]), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module 'stitchswitch' has no attribute {name!r}")


def __dir__():
    return sorted(set(globals()) | set(_LAZY))
