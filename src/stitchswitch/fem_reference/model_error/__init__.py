"""The model-error check: the reduced model against the independent shell of revolution
(``stitchswitch fem-check``, docs/fem-reference.md).

* ``budget``: ``BUDGET`` (per keypoint, half of the paper's validation error), ``KEYS``;
* ``table``: ``model_error(designs, material, params) -> ModelErrorTable`` of ``DesignError``
  rows (gap per keypoint, its attribution to each physics switch, the remainder);
* ``text``: ``table_text(result)``.
"""
from stitchswitch.fem_reference.model_error.budget import BUDGET, KEYS
from stitchswitch.fem_reference.model_error.table import (
                                                          DEFAULT_DESIGNS,
                                                          DesignError,
                                                          ModelErrorTable,
                                                          design_error,
                                                          model_error,
)
from stitchswitch.fem_reference.model_error.text import table_text

__all__ = ["BUDGET", "DEFAULT_DESIGNS", "KEYS", "DesignError", "ModelErrorTable",
           "design_error", "model_error", "table_text"]
