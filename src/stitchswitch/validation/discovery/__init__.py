"""Discrepancy discovery (docs/discovery.md): where the model and the data disagree, which
missing effect explains it, and how much the gap shrinks once it is added.

* ``workflow``: ``discover(data, material, DiscoveryConfig) -> Discovery``.
* ``space``: the fitted parameters (``ModelSpec``); ``evaluate``: cached keypoints of many
  (design, parameters) pairs; ``fit``: least-squares fits; ``cv``: cross-validation and the F test;
  ``residuals``: is a residual pattern systematic, its systematic part and the noise;
  ``signature``: sensitivity signatures; ``proposal``: the next samples that best separate the
  leading models.
* ``report``, ``figures``: the report (Markdown, HTML, JSON); ``synthetic``: SYNTHETIC datasets
  with a hidden effect, and how much of it a recalibration cannot absorb.
* ``effects/``: the library of candidate effects; ``noise/``: Huber's robust loss and the fit
  for noise proportional to the keypoint size.

Imports ``reduced`` and ``validation.measured`` / ``metrics``.
"""
