"""Calibration of the material against measured keypoints (paper, section 4).

* ``evolution``: ``calibrate`` (differential evolution), ``CalibrationResult``,
  ``identifiability``, ``predict_keypoints``, the parameter ``BOUNDS``.

Imports ``reduced.model`` and ``reduced.solvers``.
"""
