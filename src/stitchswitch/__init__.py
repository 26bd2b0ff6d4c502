"""stitchswitch: design and fabrication of bistable embroidered textiles.

Internal length unit: millimetres, measured in the *rest frame* of the relaxed fabric
unless a name says otherwise (``diameter_mm`` is measured on the pre-stretched fabric,
as in the paper). The reduced model works internally in units of the node spacing dR
(see ``docs/model.md``); everything it returns is converted back to mm.
"""
from stitchswitch.errors import StitchSwitchError, InvalidInputError
from stitchswitch.reduced.params import Material, Patch, DEFAULT_MATERIAL
from stitchswitch.reduced.solve import solve, Solution
from stitchswitch.reduced.keypoints import keypoints, Keypoints

__version__ = "0.1.0"
__all__ = [
    "StitchSwitchError", "InvalidInputError", "Material", "Patch", "DEFAULT_MATERIAL",
    "solve", "Solution", "keypoints", "Keypoints", "__version__",
]
