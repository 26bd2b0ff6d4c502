"""Calibration of the material against measured keypoints (paper, section 4), and how much each
parameter matters.

* ``evolution``: ``calibrate`` (differential evolution), ``CalibrationResult``,
  ``identifiability``, ``predict_keypoints``, the parameter ``BOUNDS``.
* ``designs``: ``CALIBRATION_DESIGNS``, the paper's 25 calibration designs.
* ``sensitivity``: ``sensitivity(material, designs, step) -> Sensitivity``, the elasticity of each
  keypoint with respect to each material parameter (``stitchswitch sensitivity``).

Imports ``reduced.model`` and ``reduced.solvers``.
"""
