"""How the discovery fits treat measurement noise that is not plain, equal Gaussian noise.

* ``robust``: Huber's loss by pseudo-observations (``winsorize``, ``robust_scale``), so an
  outlying measurement pulls no fit by more than a few robust standard deviations.
* ``proportional``: noise proportional to the keypoint size (``KeypointScale``,
  ``ScaledEvaluator``, ``SIZE_FLOOR_MM``): the fit on keypoints divided by their smooth size.

Imports ``validation.discovery.residuals``; used by ``workflow``.
"""
