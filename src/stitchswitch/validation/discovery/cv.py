"""Held-out error and significance for model comparison.

* ``fold_labels``: K folds over the distinct training designs (rows of one design stay
  together): a design's fold is a seeded hash of its (d, p), so adding rows (the proposed next
  samples, measured) leaves the folds of the rows already there as they were. A balanced
  permutation would re-deal every fold when a design is added, and the verdict would change
  with the new partition, not with what the new rows say. The folds are balanced on average
  only (binomial sizes).
* ``cross_validate``: for each fold, refit every parameter on the other folds by least squares
  started at the full-data fit (its finite-difference Jacobian is cached, so the first step is
  free) with at most ``max_nfev`` steps and, with ``radius``, within ``radius`` of it in every
  coordinate (``fit.fit``), and predict the held-out designs (their branch chosen as the
  evaluator does). The score is the mean squared error (mm^2) of those held-out predictions
  over the five keypoints. A fold refit estimates how the fit moves without a fifth of the
  rows: a step far outside the full fit's neighbourhood leaves its basin, and on bistable data
  another basin fits the fold's rows by other branches and predicts the held-out ones badly
  (measured: ``docs/discovery.md``, "The fold refit's radius").
  A fold whose refit ends where it started (its steps were all rejected within the budget) is
  counted as stuck: its held-out rows are predicted by the full fit, which saw them, so with
  stuck folds the score is partly a training error.
* ``cross_validate_stepped``: every fold is one Levenberg-Marquardt step from the full-data
  fit on the fold's training rows (the full fit's Jacobian, restricted to those rows; damping
  ``damping`` times the diagonal of J^T J; within ``radius``), and the held-out designs are
  solved at the stepped parameters warm-started from the full fit's equilibria of the same
  designs (the branch the full fit predicts them on). A fold is then never stuck, and its
  step is the linear estimate of how far the fit moves without those rows, which is what the
  refit approximates with its few steps; the warm start keeps a held-out bistable design on
  its branch, so a small step does not read as a jump. No fold costs a refit: one Jacobian
  (usually cached from the fit) and one warm solve per held-out design.
  Cross-validation is the complexity penalty: an extra parameter that only fits noise makes
  the held-out predictions worse, not better.
* ``f_test``: is the drop of the training residual sum of squares from adding m parameters
  larger than the noise explains? F = ((RSS0 - RSS1) / m) / (RSS1 / (n - k1)), the noise
  variance estimated from the larger model's residuals; p from the F(m, n - k1) distribution.
* ``oracle_power``: the power of that F test with one extra parameter when the true effect
  leaves a residual of noncentrality lambda that no recalibration absorbs (the benchmark's
  detectability, the absorbability table of docs/discovery.md).
* ``sign_flip_test``: one-sided randomization test that paired per-design differences have a
  positive mean (random sign flips, seeded).
* ``within_noise``: which models' held-out losses are not significantly worse than the best
  one's (that sign-flip test on the paired per-row differences, p >= alpha): the data cannot
  tell them from the best.
* ``validation_score``: the noise-weighted mean absolute error on the file's validation rows,
  sum over keypoints of MAE_q / sigma_q (sigma: the estimated noise floor), so that each
  keypoint counts by how far above its noise it is missed. A named effect must lower it: an
  effect that fits the training rows but predicts rows it never saw worse is a stand-in, not
  the missing physics.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from stitchswitch.validation.discovery.fit import fit, jacobian, trust_box

__all__ = ["fold_labels", "CrossValidation", "cross_validate", "cross_validate_stepped",
           "damped_step", "f_test", "oracle_power", "sign_flip_test", "within_noise",
           "validation_score"]


def fold_labels(designs, k: int, seed: int) -> np.ndarray:
    """Fold index (0..k-1) of every row; rows of the same design share a fold, and a design's
    fold depends only on the design, ``k`` and ``seed``."""
    import hashlib

    keys = [(float(d), float(p)) for d, p in designs]
    k = max(2, min(int(k), len(set(keys))))

    def fold(key):
        h = hashlib.blake2b(f"{seed}:{key[0]!r}:{key[1]!r}".encode(), digest_size=8)
        return int(int.from_bytes(h.digest(), "big") * k >> 64)

    return np.array([fold(key) for key in keys])


@dataclass(frozen=True)
class CrossValidation:
    """Held-out predictions (n, 5) of every training row and their mean squared error."""

    predictions: np.ndarray
    row_loss: np.ndarray         # mean squared error of each row over the five keypoints
    score_mm2: float
    fold_parameters: tuple       # x of each fold's refit
    stuck_folds: int = 0         # folds whose refit kept the full fit's parameters exactly

    @property
    def folds(self) -> int:
        return len(self.fold_parameters)


def cross_validate(spec, ev, designs, measured, x_full, labels, *, max_nfev: int = 3,
                   radius: float | None = None) -> CrossValidation:
    designs = [tuple(map(float, d)) for d in designs]
    measured = np.asarray(measured, dtype=float)
    pred = np.empty_like(measured)
    xs = []
    for test, train_d, test_d in _folds(designs, labels):
        f = fit(spec, ev, train_d, measured[~test], x_full, max_nfev=max_nfev, radius=radius)
        xs.append(f.x)
        pred[test] = ev.one(spec, f.x, test_d)
    return _scored(pred, measured, xs, x_full)


def _folds(designs, labels):
    """(held-out mask, training designs, held-out designs) of every non-empty fold, in order."""
    for k in range(int(labels.max()) + 1):
        test = labels == k
        if test.any():
            yield (test, [d for d, t in zip(designs, test) if not t],
                   [d for d, t in zip(designs, test) if t])


def _scored(pred, measured, xs, x_full) -> CrossValidation:
    loss = np.mean((pred - measured) ** 2, axis=1)
    start = np.asarray(x_full, dtype=float)
    stuck = sum(bool(np.array_equal(np.asarray(x, dtype=float), start)) for x in xs)
    return CrossValidation(pred, loss, float(np.mean(loss)), tuple(xs), stuck)


def damped_step(J, residual, damping: float) -> np.ndarray:
    """The Levenberg-Marquardt step dx minimizing |J dx - residual|^2 + damping |D dx|^2, D^2
    the diagonal of J^T J (scale-free; a column without influence gets no step)."""
    J, residual = np.asarray(J, dtype=float), np.asarray(residual, dtype=float)
    D = np.sqrt(damping * np.sum(J * J, axis=0))
    A = np.vstack([J, np.diag(D)])
    b = np.concatenate([residual, np.zeros(J.shape[1])])
    return np.linalg.lstsq(A, b, rcond=None)[0]


def cross_validate_stepped(spec, ev, designs, measured, x_full, labels, *, damping: float = 0.1,
                           radius: float | None = None) -> CrossValidation:
    """Every fold one damped step from ``x_full`` (module docstring); the held-out designs
    solved at it warm-started from ``x_full``'s equilibria (``Evaluator.perturbed``)."""
    designs = [tuple(map(float, d)) for d in designs]
    measured = np.asarray(measured, dtype=float)
    x_full, (lo, hi), box = trust_box(spec, x_full, radius)
    J = jacobian(spec, ev, designs, x_full, lo, hi)
    residual = measured - ev.one(spec, x_full, designs)
    pred = np.empty_like(measured)
    xs = []
    for test, _, test_d in _folds(designs, labels):
        rows = np.repeat(~test, measured.shape[1])
        dx = damped_step(J[rows], residual[~test].ravel(), damping)
        x = np.clip(x_full + dx, *box)
        xs.append(x)
        pred[test] = ev.perturbed(spec, x_full, [x], test_d)[0]
    return _scored(pred, measured, xs, x_full)


def f_test(rss0: float, rss1: float, n: int, k0: int, k1: int) -> tuple[float, float]:
    """(F, p) of the nested comparison; p = 1 when the larger model does not fit better."""
    from scipy.stats import f as f_dist

    m, dof = k1 - k0, n - k1
    if m <= 0 or dof <= 0 or rss1 <= 0 or rss0 <= rss1:
        return 0.0, 1.0
    F = ((rss0 - rss1) / m) / (rss1 / dof)
    return float(F), float(f_dist.sf(F, m, dof))


def oracle_power(lam: float, n: int, k1: int, alpha: float) -> float:
    """P(F > F_crit(alpha; 1, n - k1)) for the noncentral F(1, n - k1, ``lam``): how often an
    oracle's F test (n residuals, k1 parameters of the larger model) passes at level ``alpha``."""
    from scipy.stats import f as f_dist
    from scipy.stats import ncf

    if lam <= 0:
        return 0.0
    return float(ncf.sf(f_dist.isf(alpha, 1, n - k1), 1, n - k1, lam))


def sign_flip_test(diff, permutations: int = 10000, seed: int = 0) -> float:
    """p-value of mean(diff) > 0 under random signs (add-one corrected)."""
    diff = np.asarray(diff, dtype=float)
    observed = diff.mean()
    signs = np.random.default_rng(seed).choice((-1.0, 1.0), size=(permutations, diff.size))
    null = (signs * diff).mean(axis=1)
    return float((1 + np.count_nonzero(null >= observed)) / (permutations + 1))


def within_noise(best_loss, others: dict, alpha: float, seed: int = 0) -> list:
    """Names of ``others`` ({name: per-row held-out loss}) whose loss is not significantly
    larger than ``best_loss`` (paired one-sided sign-flip test, p >= ``alpha``)."""
    best_loss = np.asarray(best_loss, dtype=float)
    return [name for name, loss in others.items()
            if sign_flip_test(np.asarray(loss, dtype=float) - best_loss, seed=seed) >= alpha]


def validation_score(pred, measured, sigma_mm) -> float:
    """sum_q mean_i |pred - measured|_iq / sigma_q over the validation rows (n, 5); NaN with no
    rows."""
    pred, measured = np.asarray(pred, dtype=float), np.asarray(measured, dtype=float)
    if len(measured) == 0:
        return float("nan")
    return float(np.sum(np.mean(np.abs(pred - measured), axis=0) / np.asarray(sigma_mm)))
