"""Agreement between predicted and measured keypoints, per quantity and split (paper, Table 1).

For one quantity over the n rows of a split, with measured values m_i and predictions y_i (mm):

* ``mae_mm``: the mean absolute error ``mean_i |y_i - m_i|`` over all n rows.
* ``pct_error``: the mean absolute percentage error
  ``mean_i 100 |y_i - m_i| / |m_i|`` over the rows with ``m_i != 0``. A measured value of
  exactly 0 (a flat patch: h = 0, or z = 0 at a point on the far fabric) has no relative error;
  such rows are left out of ``pct_error`` only, and counted in ``n_pct_skipped``. If every row
  is left out, ``pct_error`` is nan (``null`` in JSON).
* ``n``: the number of rows (all of them enter ``mae_mm``).

The paper does not define its percentage error; the mean of per-row relative errors is the
usual reading and is what this module computes. Rows whose prediction is not finite are an
error (``solve`` always returns finite keypoints).
"""
from __future__ import annotations

import math

import numpy as np

from stitchswitch.errors import InvalidInputError
from stitchswitch.validation.measured import QUANTITIES, SPLITS

__all__ = ["pct_error", "mae", "quantity_metrics", "split_metrics", "table1", "PAPER_TABLE1"]

#: The paper's Table 1 (its own measurements, 25 train and 28 validation patches), quoted for
#: comparison: percentage error and MAE (mm) per quantity.
PAPER_TABLE1 = {
    "train": {"h": {"pct_error": 14.7, "mae_mm": 1.44}, "r_a": {"pct_error": 4.5, "mae_mm": 0.87},
              "z_a": {"pct_error": 20.4, "mae_mm": 1.09}, "r_b": {"pct_error": 6.1, "mae_mm": 1.05},
              "z_b": {"pct_error": 22.9, "mae_mm": 0.93}},
    "val": {"h": {"pct_error": 24.6, "mae_mm": 2.23}, "r_a": {"pct_error": 15.8, "mae_mm": 1.82},
            "z_a": {"pct_error": 31.7, "mae_mm": 1.45}, "r_b": {"pct_error": 16.2, "mae_mm": 1.80},
            "z_b": {"pct_error": 25.8, "mae_mm": 0.99}},
}


def _pair(predicted, measured) -> tuple[np.ndarray, np.ndarray]:
    y, m = np.asarray(predicted, float), np.asarray(measured, float)
    if y.shape != m.shape:
        raise InvalidInputError(f"predicted and measured: shapes {y.shape} and {m.shape} differ")
    if not (np.all(np.isfinite(y)) and np.all(np.isfinite(m))):
        raise InvalidInputError("predicted and measured: values must be finite")
    return y, m


def pct_error(predicted, measured) -> tuple[float, int]:
    """``(mean 100 |y - m| / |m| over rows with m != 0, number of rows skipped for m == 0)``."""
    y, m = _pair(predicted, measured)
    keep = m != 0
    skipped = int(m.size - np.count_nonzero(keep))
    if not np.any(keep):
        return math.nan, skipped
    return float(np.mean(100.0 * np.abs(y[keep] - m[keep]) / np.abs(m[keep]))), skipped


def mae(predicted, measured) -> float:
    """Mean absolute error (same unit as the inputs); nan for no rows."""
    y, m = _pair(predicted, measured)
    return float(np.mean(np.abs(y - m))) if y.size else math.nan


def quantity_metrics(predicted, measured) -> dict:
    """``{"pct_error", "mae_mm", "n", "n_pct_skipped"}`` of one quantity (1D arrays)."""
    pct, skipped = pct_error(predicted, measured)
    return {"pct_error": pct, "mae_mm": mae(predicted, measured),
            "n": int(np.asarray(measured).size), "n_pct_skipped": skipped}


def split_metrics(predicted, measured) -> dict:
    """Metrics of every quantity from (n, 5) arrays, columns in the order of ``QUANTITIES``."""
    y, m = _pair(predicted, measured)
    if y.ndim != 2 or y.shape[1] != len(QUANTITIES):
        raise InvalidInputError(f"predicted and measured: shape {y.shape} is not (n, 5)")
    return {q: quantity_metrics(y[:, k], m[:, k]) for k, q in enumerate(QUANTITIES)}


def table1(data, predicted) -> dict:
    """Table-1 structure ``{"train": {"h": {...}, ...}, "val": {...}}`` for ``MeasuredData``
    ``data`` and its (n, 5) predictions (rows in the order of ``data.rows``)."""
    y = np.asarray(predicted, float)
    if y.shape != (len(data.rows), len(QUANTITIES)):
        raise InvalidInputError(f"predicted: shape {y.shape}, expected ({len(data.rows)}, 5)")
    measured = data.keypoints()
    splits = np.array([r.split for r in data.rows])
    return {s: split_metrics(y[splits == s], measured[splits == s]) for s in SPLITS}
