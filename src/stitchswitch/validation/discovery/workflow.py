"""Discrepancy discovery: find where the model and the data disagree, name the missing effect,
add it, and show the gap shrink on the validation rows.

``discover(data, start, config)`` runs five steps, each recorded in the result:

1. **Calibrate the starting model** on the training rows: its free coefficients
   (``discovery_space.BASE_FREE``) by least squares (``discovery_fit``), optionally after a short
   differential evolution.
2. **Locate the disagreement**: residuals (measured - predicted) per quantity on every row, and
   for each quantity a cross-validated smoother-against-zero randomization test
   (``discovery_residuals``): is the pattern over (d, p) systematic or noise?
3. **Candidates**: every effect of the library (``validation.discovery.effects``) is added in turn. Its
   sensitivity signature at the calibrated starting model, and the part of it that recalibrating
   the coefficients cannot mimic, are correlated with the residuals (``discovery_signature``).
   Then all coefficients and the effect's parameters are refitted on the training rows.
4. **Rank** the candidates by K-fold cross-validated error on the training rows
   (``discovery_cv``; cross-validation is the complexity penalty: held-out error rises when an
   extra parameter fits noise). The validation rows take no part in fitting, ranking or the
   decision.
5. **Decide**: the best-ranked candidate is named only when it beats the starting model's
   cross-validated error *and* its training-error improvement is significant against the noise:
   an F test (noise variance from the extended model's residuals) at alpha / (number of
   candidates) (Bonferroni: the winner was selected among them). Otherwise no missing effect
   is reported. The before/after table is the validation rows' error of the calibrated starting
   model and of the model with the named effect.
"""
from __future__ import annotations

import time
from dataclasses import dataclass, field, replace

import numpy as np

from stitchswitch.errors import InvalidInputError
from stitchswitch.reduced.model.params import Material
from stitchswitch.validation.discovery.cv import cross_validate, f_test, fold_labels, sign_flip_test
from stitchswitch.validation.discovery.effects import LIBRARY, get_effect
from stitchswitch.validation.discovery.evaluate import Evaluator
from stitchswitch.validation.discovery.fit import fit, fit_effect, jacobian
from stitchswitch.validation.discovery.residuals import residual_analysis
from stitchswitch.validation.discovery.signature import explain, signature
from stitchswitch.validation.discovery.space import BASE_FREE, ModelSpec
from stitchswitch.validation.measured import QUANTITIES, MeasuredData
from stitchswitch.validation.metrics import split_metrics

__all__ = ["DiscoveryConfig", "Candidate", "Discovery", "discover", "stage_count"]


@dataclass(frozen=True)
class DiscoveryConfig:
    """Settings of the workflow. ``effects``: candidate names (None: the whole library).
    ``folds``: K of the cross-validation. ``alpha``: family-wise significance level.
    ``de_generations``: differential-evolution generations before the starting model's least
    squares (0: least squares from the starting material only), population ``de_popsize``.
    ``fit_max_nfev`` / ``cv_max_nfev``: least-squares steps of a full fit / of a fold refit.
    ``scan_points``: magnitudes of the strength scan. ``permutations``: of the residual test."""

    effects: tuple | None = None
    folds: int = 5
    alpha: float = 0.05
    seed: int = 0
    de_generations: int = 0
    de_popsize: int = 6
    fit_max_nfev: int = 25
    cv_max_nfev: int = 3
    scan_points: int = 5
    permutations: int = 2000

    def __post_init__(self) -> None:
        names = tuple(self.effects) if self.effects is not None else tuple(LIBRARY)
        if not names:
            raise InvalidInputError("effects: give at least one candidate effect")
        for n in names:
            get_effect(n)
        if len(set(names)) != len(names):
            raise InvalidInputError(f"effects: {', '.join(names)} names an effect twice")
        object.__setattr__(self, "effects", names)
        if not 0.0 < self.alpha < 1.0:
            raise InvalidInputError(f"alpha: {self.alpha!r} is outside (0, 1)")
        for name in ("folds", "fit_max_nfev", "cv_max_nfev", "scan_points", "permutations"):
            if int(getattr(self, name)) < (2 if name == "folds" else 1):
                raise InvalidInputError(f"{name}: {getattr(self, name)!r} is too small")
        if self.de_generations < 0:
            raise InvalidInputError(f"de_generations: {self.de_generations!r} must be >= 0")

    def as_dict(self) -> dict:
        return {k: (list(v) if isinstance(v, tuple) else v) for k, v in self.__dict__.items()}


@dataclass(frozen=True)
class Candidate:
    """One candidate effect, refitted on the training rows and cross-validated: errors in mm^2
    (MSE) and mm (MAE per quantity), the F test against the starting model, the fitted
    coefficients and effect parameters, the signature correlation (``signature.explain``).
    ``spec`` and ``x`` are the fit itself (the extended model and its parameter vector), kept
    for the decision and left out of ``as_dict`` (the entry of report.json's ranking). ``rank``:
    1 for the lowest cross-validated error, set once all candidates are in."""

    effect: str
    cv_mse_mm2: float
    cv_improvement_mm2: float
    cv_sign_flip_p: float
    train_mse_mm2: float
    f_statistic: float
    p_value: float
    significant: bool
    n_parameters: int
    parameters: dict
    effect_parameters: dict
    val_mae_before_mm: dict
    val_mae_after_mm: dict
    signature: dict
    uncertified_solves: int
    fit_start: str
    spec: ModelSpec = field(repr=False, compare=False)
    x: np.ndarray = field(repr=False, compare=False)
    rank: int | None = None

    def as_dict(self) -> dict:
        return {"effect": self.effect, "score": self.cv_mse_mm2,
                "cv_improvement_mm2": self.cv_improvement_mm2,
                "cv_sign_flip_p": self.cv_sign_flip_p, "train_mse_mm2": self.train_mse_mm2,
                "f_statistic": self.f_statistic, "p_value": self.p_value,
                "significant": self.significant, "n_parameters": self.n_parameters,
                "parameters": dict(self.parameters),
                "effect_parameters": dict(self.effect_parameters),
                "val_mae_before": dict(self.val_mae_before_mm),
                "val_mae_after": dict(self.val_mae_after_mm), "signature": self.signature,
                "uncertified_solves": self.uncertified_solves, "fit_start": self.fit_start,
                "rank": self.rank}


@dataclass(frozen=True)
class Discovery:
    """The result: ``summary`` (JSON-able, deterministic: what report.json holds, its ranking
    the ``as_dict`` of ``ranking``), the candidates best first (``ranking``) and the arrays
    behind the figures (every row of the data, in file order)."""

    summary: dict
    ranking: tuple[Candidate, ...]
    diameter_mm: np.ndarray
    fill: np.ndarray
    split: np.ndarray
    measured: np.ndarray
    before: np.ndarray
    after: np.ndarray
    signatures: dict = field(default_factory=dict)   # name -> {"per_unit" (n, 5), "pattern" (n_train, 5)}
    elapsed_s: float = 0.0
    solves: int = 0

    @property
    def missing_effect(self):
        return self.summary["missing_effect"]


def stage_count(config: DiscoveryConfig) -> int:
    """Number of progress stages of ``discover`` (for a progress bar)."""
    return 3 + 2 * len(config.effects)


def _metrics(pred, measured) -> dict:
    full = split_metrics(pred, measured)
    return {q: {"mae_mm": full[q]["mae_mm"], "pct_error": full[q]["pct_error"]} for q in QUANTITIES}


def _start_fit(base, ev, designs, measured, start, config, executor):
    x0 = base.encode(start)
    if config.de_generations > 0:
        from stitchswitch.reduced.calibration.evolution import calibrate

        res = calibrate(designs, measured, start, maxiter=config.de_generations,
                        popsize=config.de_popsize, seed=config.seed, executor=executor,
                        free=base.free, check_identifiability=False)
        x0 = base.encode(res.material)
    return fit(base, ev, designs, measured, x0, max_nfev=config.fit_max_nfev)


def discover(data: MeasuredData, start: Material, config: DiscoveryConfig = DiscoveryConfig(), *,
             executor=None, progress=None, start_label: str = "default") -> Discovery:
    """Run the workflow on ``data`` from the starting material ``start``; see the module
    docstring. ``executor``: a map-like for parallel solves. ``progress(message, stage,
    total)`` is called as each stage starts."""
    t0 = time.perf_counter()
    total = stage_count(config)
    stage = [0]

    def step(message):
        if progress:
            progress(message, stage[0], total)
        stage[0] += 1

    rows = data.rows
    d_all = np.array([r.diameter_mm for r in rows])
    p_all = np.array([r.fill for r in rows])
    split = np.array([r.split for r in rows])
    measured = data.keypoints()
    tr, va = split == "train", split == "val"
    designs = [(float(d), float(p)) for d, p in zip(d_all, p_all)]
    d_tr = [x for x, t in zip(designs, tr) if t]
    d_va = [x for x, t in zip(designs, va) if t]
    m_tr, m_va = measured[tr], measured[va]
    n_res = m_tr.size
    ev = Evaluator(executor)

    # 1. the starting model, calibrated
    step("calibrating the starting model")
    base = ModelSpec(start, None, BASE_FREE)
    fb = _start_fit(base, ev, d_tr, m_tr, start, config, executor)
    before = np.empty_like(measured)
    before[tr] = fb.predictions
    before[va] = ev.one(base, fb.x, d_va)
    rss0 = float(np.sum((fb.predictions - m_tr) ** 2))

    # 2. where is it wrong?
    step("residual analysis and cross-validation of the starting model")
    res_before = residual_analysis(d_all, p_all, measured - before, QUANTITIES,
                                   alpha=config.alpha, permutations=config.permutations,
                                   seed=config.seed)
    labels = fold_labels(d_tr, config.folds, config.seed)
    cv0 = cross_validate(base, ev, d_tr, m_tr, fb.x, labels, max_nfev=config.cv_max_nfev)
    J0 = jacobian(base, ev, d_tr, fb.x, *base.bounds())

    # 3-4. every candidate: signature, refit, cross-validation
    m = len(config.effects)
    candidates, sigs = [], {}
    for name in config.effects:
        spec = base.with_effect(name)
        step(f"{name}: signature and refit")
        sig = signature(spec, ev, designs, fb.x)
        why = explain(J0, sig[tr], m_tr - fb.predictions, QUANTITIES)
        sigs[name] = {"per_unit": sig, "pattern": why.pop("pattern")}
        f, how = fit_effect(spec, ev, d_tr, m_tr, fb, J0, sig[tr], max_nfev=config.fit_max_nfev,
                            scan_points=config.scan_points)
        step(f"{name}: cross-validation")
        cv = cross_validate(spec, ev, d_tr, m_tr, f.x, labels, max_nfev=config.cv_max_nfev)
        rss1 = float(np.sum((f.predictions - m_tr) ** 2))
        F, p = f_test(rss0, rss1, n_res, base.size, spec.size)
        pred_va = ev.one(spec, f.x, d_va)
        candidates.append(Candidate(
            effect=name,
            cv_mse_mm2=cv.score_mm2,
            cv_improvement_mm2=cv0.score_mm2 - cv.score_mm2,
            cv_sign_flip_p=sign_flip_test(cv0.row_loss - cv.row_loss, seed=config.seed),
            train_mse_mm2=f.mse_mm2,
            f_statistic=F, p_value=p,
            significant=bool(p < config.alpha / m and cv.score_mm2 < cv0.score_mm2),
            n_parameters=spec.size,
            parameters=dict(f.parameters),
            effect_parameters=dict(zip(spec.names[len(base.free):], spec.decode(f.x)[1][name])),
            val_mae_before_mm={q: v["mae_mm"] for q, v in _metrics(before[va], m_va).items()},
            val_mae_after_mm={q: v["mae_mm"] for q, v in _metrics(pred_va, m_va).items()},
            signature=why,
            uncertified_solves=f.uncertified,
            fit_start=how["start"],
            spec=spec, x=f.x))
    ranking = tuple(replace(c, rank=rank) for rank, c in enumerate(
        sorted(candidates, key=lambda c: (c.cv_mse_mm2, c.n_parameters, c.effect)), start=1))

    # 5. decide, add the winner, show the gap
    step("decision and the validation gap")
    top = ranking[0]
    winner = top if top.significant else None
    after = before.copy()
    if winner:
        after[tr] = ev.one(winner.spec, winner.x, d_tr)
        after[va] = ev.one(winner.spec, winner.x, d_va)
    res_after = residual_analysis(d_all, p_all, measured - after, QUANTITIES, alpha=config.alpha,
                                  permutations=config.permutations, seed=config.seed)
    threshold = config.alpha / m
    if winner:
        reason = (f"{top.effect} has the lowest cross-validated error ({top.cv_mse_mm2:.3f} "
                  f"against {cv0.score_mm2:.3f} mm^2 for the starting model) and its improvement "
                  f"is significant: F = {top.f_statistic:.1f}, p = {top.p_value:.2g} < "
                  f"{threshold:.2g} (alpha {config.alpha:g} / {m} candidates)")
    elif top.cv_mse_mm2 >= cv0.score_mm2:
        reason = (f"no candidate lowers the cross-validated error of the starting model "
                  f"({cv0.score_mm2:.3f} mm^2; best {top.effect} {top.cv_mse_mm2:.3f})")
    else:
        reason = (f"the best candidate, {top.effect}, lowers the cross-validated error "
                  f"({top.cv_mse_mm2:.3f} against {cv0.score_mm2:.3f} mm^2) but not "
                  f"significantly: p = {top.p_value:.2g} >= {threshold:.2g}")
    summary = {
        "missing_effect": winner.effect if winner else None,
        "significant": bool(winner),
        "effect_parameters": dict(winner.effect_parameters) if winner else {},
        "decision": reason,
        "ranking": [c.as_dict() for c in ranking],
        "before": _metrics(before[va], m_va),
        "after": _metrics(after[va], m_va),
        "starting_model": {
            "label": start_label, "free": list(base.free),
            "parameters": fb.parameters, "train_mse_mm2": fb.mse_mm2,
            "cv_score_mm2": cv0.score_mm2, "uncertified_solves": fb.uncertified},
        "residuals_before": res_before,
        "residuals_after": res_after,
        "significance_threshold": threshold,
        "n_train": int(tr.sum()), "n_val": int(va.sum()),
        "config": config.as_dict(),
    }
    return Discovery(summary=summary, ranking=ranking, diameter_mm=d_all, fill=p_all, split=split,
                     measured=measured, before=before, after=after, signatures=sigs,
                     elapsed_s=time.perf_counter() - t0, solves=ev.calls)


