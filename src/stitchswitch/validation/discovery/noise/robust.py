"""A robust fit against outlying measurements: Huber's loss by pseudo-observations.

Huber's M-estimate with a fixed scale is the least-squares fit to *pseudo-observations*
y* = f + psi(y - f), psi the residual clipped to [-c s, c s] (Huber 1981, "metrically
winsorized residuals"; iterating fit and clipping converges to the M-estimate). ``winsorize``
is one such step: the scale s of each quantity is the normalized median absolute deviation of
the residuals (1.4826 MAD, robust against the outliers themselves), and every measured value
whose residual exceeds c s is moved to f +- c s. The workflow alternates it with the starting
model's fit a few times and fits every candidate to the pseudo-observations, so an outlier
pulls no fit by more than c s; the entries moved are the down-weighted rows of the report
(their Huber weight c s / |r| < 1).
"""
from __future__ import annotations

import numpy as np

__all__ = ["robust_scale", "winsorize"]


def robust_scale(residuals) -> np.ndarray:
    """1.4826 x the median absolute deviation of each column (floored at 1e-6)."""
    r = np.asarray(residuals, dtype=float)
    med = np.median(r, axis=0)
    return np.maximum(1.4826 * np.median(np.abs(r - med), axis=0), 1e-6)


def winsorize(measured, predicted, c: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(pseudo-observations, Huber weights (n, 5), scale (5,)) of one step."""
    measured = np.asarray(measured, dtype=float)
    r = measured - np.asarray(predicted, dtype=float)
    s = robust_scale(r)
    limit = c * s
    clipped = np.clip(r, -limit, limit)
    weights = np.where(np.abs(r) > limit, limit / np.maximum(np.abs(r), 1e-300), 1.0)
    return predicted + clipped, weights, s
