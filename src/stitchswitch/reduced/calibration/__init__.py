"""Calibration of the material against measured keypoints (paper, section 4), and how much each
parameter matters.

* ``evolution``: ``calibrate`` (differential evolution and a least-squares polish),
  ``CalibrationResult``, ``identifiability``, ``predict_keypoints`` (optionally on an executor),
  ``PARAMS``, ``BOUNDS``, ``DE_TOL`` (the search's termination tolerance).
* ``checkpoint``: ``checkpoint_path`` / ``provenance_path`` (the files next to a calibrated
  material) and ``resume_point`` (the best material of a previous run, checked).
* ``designs``: ``CALIBRATION_DESIGNS``, the paper's 25 calibration designs.
* ``magnitudes``: ``fit_magnitudes``, a material fitted to the mean keypoints the paper's Table 1
  implies and to its qualitative findings (how the default material was made), ``evaluate``.
* ``sensitivity``: ``sensitivity(material, designs, step) -> Sensitivity``, the elasticity of each
  keypoint with respect to each material parameter (``stitchswitch sensitivity``).

Imports ``reduced.model`` and ``reduced.solvers``.
"""
