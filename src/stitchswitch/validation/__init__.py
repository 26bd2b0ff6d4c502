"""Measured data and the model's agreement with it.

* ``measured``: the samples CSV and its validating loader (``MeasuredData``).
* ``metrics``: Table-1 errors per quantity and split.
* ``report``: ``stitchswitch validate``'s report (Markdown, HTML, JSON, plots).
* ``reference_truth``: the hidden "true" material of the synthetic datasets.
* ``discovery/``: discrepancy discovery and its library of candidate effects.

Imports ``reduced``; nothing below imports it.
"""
