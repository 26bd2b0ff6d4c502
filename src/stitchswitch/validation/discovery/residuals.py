"""Is a residual pattern over the design space systematic, or noise?

For one quantity, the residuals e_i (measured - predicted, mm) at designs (d_i, p_i):

* the **smoother** is a quadratic surface in the standardized (d, p) (six coefficients, least
  squares); its leave-one-out residuals come from the hat matrix, e_i^loo = (e - H e)_i /
  (1 - H_ii);
* the statistic is the cross-validated R^2 against predicting zero,
  T = 1 - mean(e^loo^2) / mean(e^2): how much of the residual a smooth function of the design
  predicts on rows it has not seen (a constant offset counts as systematic too);
* the p-value is a randomization test: T is recomputed for ``permutations`` random
  permutations of the residuals over the designs combined with random sign flips (seeded); under
  the null hypothesis "independent, symmetric, zero-mean noise" every such reshuffle is equally
  likely. p = (1 + #{T_b >= T}) / (1 + B).

This is the cross-validation route (no replicate samples are needed for a noise
estimate). A quantity is *systematic* when p < alpha / 5 (Bonferroni over the five keypoints).

``smooth_split`` splits residuals into the smoother's fit (the *systematic part*, what a smooth
function of the design explains) and an estimate of the noise: the residual standard error of
that fit, sqrt(|e - H e|^2 / (n - 6)), unbiased for the noise sigma when the surface holds the
systematic part. ``systematic_energy`` = max(0, |H e|^2 - 6 sigma^2) / n is the mean squared
systematic residual with the noise the six-term fit absorbs taken out; ``energy_se`` =
sigma^2 sqrt(12) / n its standard deviation under pure noise (|H e|^2 is sigma^2 chi^2(6)).
``not_shrunk`` uses it to tell a claimed keypoint whose systematic part grew from one whose
estimate moved within the noise.
"""
from __future__ import annotations

import numpy as np

__all__ = ["design_basis", "loo_r2", "systematic_test", "residual_analysis", "smooth_split",
           "not_shrunk", "CLAIM_SE"]


def design_basis(d, p, like=None) -> np.ndarray:
    """(n, 6) quadratic basis in d and p standardized by their own mean and standard deviation,
    or by those of ``like`` ((d, p) of other designs: the basis a surface fitted there is
    evaluated in)."""
    d, p = np.asarray(d, float), np.asarray(p, float)
    d0, p0 = (d, p) if like is None else (np.asarray(like[0], float), np.asarray(like[1], float))
    u = (d - d0.mean()) / (d0.std() or 1.0)
    v = (p - p0.mean()) / (p0.std() or 1.0)
    return np.stack([np.ones_like(u), u, v, u * u, u * v, v * v], axis=1)


def _hat(X: np.ndarray) -> np.ndarray:
    return X @ np.linalg.pinv(X)


def loo_r2(H: np.ndarray, E: np.ndarray) -> np.ndarray:
    """Cross-validated R^2 against zero of each column of E (n, m) under the smoother H."""
    lev = 1.0 - np.clip(np.diag(H), 0.0, 1.0 - 1e-9)
    loo = (E - H @ E) / lev[:, None]
    denom = np.mean(E * E, axis=0)
    return 1.0 - np.mean(loo * loo, axis=0) / np.where(denom > 0, denom, np.inf)


def systematic_test(d, p, e, permutations: int = 2000, seed: int = 0) -> dict:
    """{"cv_r2", "p_value", "rms_mm", "mean_mm"} of residuals ``e`` at designs (d, p)."""
    e = np.asarray(e, dtype=float)
    X = design_basis(d, p)
    H = _hat(X)
    t = float(loo_r2(H, e[:, None])[0])
    rng = np.random.default_rng(seed)
    idx = np.argsort(rng.random((permutations, e.size)), axis=1)
    signs = rng.choice((-1.0, 1.0), size=(permutations, e.size))
    null = loo_r2(H, (e[idx] * signs).T)
    p_value = float((1 + np.count_nonzero(null >= t)) / (permutations + 1))
    return {"cv_r2": t, "p_value": p_value, "rms_mm": float(np.sqrt(np.mean(e * e))),
            "mean_mm": float(np.mean(e))}


def residual_analysis(d, p, residuals, quantities, *, alpha: float = 0.05,
                      permutations: int = 2000, seed: int = 0) -> dict:
    """``systematic_test`` for every column of ``residuals`` (n, 5), plus ``systematic``."""
    out = {}
    for k, q in enumerate(quantities):
        res = systematic_test(d, p, residuals[:, k], permutations, seed + k)
        res["systematic"] = bool(res["p_value"] < alpha / len(quantities))
        out[q] = res
    return out


def smooth_split(d, p, residuals) -> dict:
    """Per column of ``residuals`` (n, m): {"systematic_rms_mm": RMS of H e, "noise_sigma_mm":
    residual standard error of the quadratic surface, "systematic_energy_mm2"} (lists)."""
    E = np.asarray(residuals, dtype=float)
    X = design_basis(d, p)
    H = _hat(X)
    n, rank = E.shape[0], int(np.linalg.matrix_rank(X))
    fitted = H @ E
    sigma = np.sqrt(np.sum((E - fitted) ** 2, axis=0) / max(n - rank, 1))
    energy = np.maximum(0.0, np.sum(fitted ** 2, axis=0) - rank * sigma ** 2) / n
    # |H e|^2 of pure noise is sigma^2 chi^2(rank): its standard deviation over n
    se = sigma ** 2 * np.sqrt(2.0 * rank) / n
    return {"systematic_rms_mm": np.sqrt(np.mean(fitted ** 2, axis=0)).tolist(),
            "noise_sigma_mm": sigma.tolist(), "systematic_energy_mm2": energy.tolist(),
            "energy_se_mm2": se.tolist()}


#: A claimed keypoint's systematic energy may grow by at most this many of its standard errors
#: under noise (``smooth_split``'s ``energy_se_mm2``) before it counts as not shrunk.
CLAIM_SE = 2.0


def not_shrunk(before: dict, after: dict, columns) -> list[int]:
    """The ``columns`` (indices) of the claimed keypoints whose systematic residual the change
    from ``before`` to ``after`` (two ``smooth_split`` results) did not shrink: all of them when
    their summed mean square systematic part (``systematic_rms_mm`` squared) did not fall, else
    those whose own grew by more than ``CLAIM_SE`` standard errors of its noise (a 0.1 mm move
    of a smooth part estimated from 25 noisy rows is not a growth). Every keypoint whose RMS
    falls passes, so this never blocks what requiring each RMS to fall would pass."""
    m0 = np.asarray(before["systematic_rms_mm"]) ** 2
    m1 = np.asarray(after["systematic_rms_mm"]) ** 2
    se = np.asarray(before["energy_se_mm2"])
    cols = list(columns)
    if cols and np.sum(m1[cols]) >= np.sum(m0[cols]):
        return cols
    return [k for k in cols if m1[k] - m0[k] > CLAIM_SE * se[k]]
