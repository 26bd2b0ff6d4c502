"""Sensitivity signatures: how an effect moves the keypoints, and whether that matches the
residuals.

``signature``: the change of the five keypoints per unit of the effect's first parameter, at
the starting model's fitted coefficients, by a finite difference from zero to the parameter's
probe value (a secant; for ``boundary_transition`` the derivative at exactly zero vanishes,
because widths below one node spacing change nothing).

``explain``: recalibrating the starting model's coefficients can absorb the part of a signature
that lies in the span of their own Jacobian J. What it cannot absorb is s_perp = (I - P_J) s.
The correlation of s_perp with the starting model's training residuals e (measured - predicted)
says how well the effect explains what the starting model cannot fit; ``step`` = <s_perp, e> /
|s_perp|^2 is the strength a linearized refit would choose (its sign tells the direction), and
``unabsorbed`` = |s_perp| / |s| how much of the effect the coefficients cannot mimic.
"""
from __future__ import annotations

import numpy as np

__all__ = ["signature", "explain"]


def signature(spec, ev, designs, x_base) -> np.ndarray:
    """(n, 5) keypoint change per unit of the first effect parameter at ``x_base``."""
    probe = spec.effect_parameters[0].probe
    rest = tuple(0.0 for _ in spec.effect_parameters[1:])
    zero = spec.extend(x_base, (0.0,) + rest)
    on = spec.extend(x_base, (probe,) + rest)
    k0, k1 = ev.keypoints(spec, [zero, on], designs)
    return (k1 - k0) / probe


def _corr(a, b) -> float:
    na, nb = np.linalg.norm(a), np.linalg.norm(b)
    return float(a @ b / (na * nb)) if na > 0 and nb > 0 else 0.0


def explain(jacobian: np.ndarray, sig: np.ndarray, residual: np.ndarray, quantities) -> dict:
    """Correlation of the unabsorbable part of ``sig`` (n, 5) with ``residual`` (n, 5), and
    ``pattern``: that part times ``step`` (n, 5), the residual a linearized refit explains."""
    s = sig.ravel()
    e = residual.ravel()
    q_, _ = np.linalg.qr(jacobian)
    s_perp = s - q_ @ (q_.T @ s)
    norm = float(s_perp @ s_perp)
    per_q = {}
    sp = s_perp.reshape(sig.shape)
    for k, q in enumerate(quantities):
        per_q[q] = _corr(sp[:, k], residual[:, k])
    step = float(s_perp @ e / norm) if norm > 0 else 0.0
    return {"correlation": _corr(s_perp, e), "raw_correlation": _corr(s, e),
            "unabsorbed": float(np.sqrt(norm) / np.linalg.norm(s)) if np.linalg.norm(s) > 0 else 0.0,
            "step": step, "per_quantity": per_q, "pattern": sp * step}
