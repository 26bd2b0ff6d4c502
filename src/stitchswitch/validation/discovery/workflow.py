"""Discrepancy discovery: find where the model and the data disagree, name the missing effect
(or say that the data cannot tell), add it, show the gap shrink on the validation rows, and
propose the samples that would decide.

``discover(data, start, config)`` runs these steps, each recorded in the result:

1. **Calibrate the starting model** on the training rows (``space.BASE_FREE``, least squares,
   optionally after a short differential evolution) at the screening resolution
   (``config.screen_nodes``, 150 nodes), then polish it at the material's own resolution.
   Optionally robust (``config.huber_c``: Huber's loss, ``robust``).
2. **Screen** every library effect at the screening resolution: its sensitivity signature and
   the part recalibration cannot absorb (``signature``), a refit of all coefficients and the
   effect (``fit.fit_effect``), and a screening score: ``cross_validate`` with a fold budget of
   one function evaluation, which takes no step, so it is the training MSE at the screening
   resolution; it only picks the leaders.
3. **Refine the leaders**: the ``config.refine`` best-screened candidates are polished,
   profiled along their strength (``fit.refine_estimate``, ``config.profile_leaders``) and
   cross-validated at full resolution
   (``cv.cross_validate_stepped``: each fold one damped step from the full fit, its held-out
   designs warm-started on the full fit's branch); a leader at zero strength is the starting
   model and takes its cross-validation. The starting model is re-polished from the
   coefficients of every leader that would pass the F test (``fit.equal_footing``): both
   sides of the nested comparison are fitted equally well, so an effect at zero strength
   cannot look significant.
4. **Decide**: a candidate passes when it lowers the starting model's
   cross-validated error, its F test against the equally polished starting model gives p <
   alpha / (number of candidates), and its strength is not zero; the decision is about the
   best-ranked passing one (``lead_candidate``). Other leaders that also improve on the
   starting model (F test at alpha) and whose held-out losses, on the cross-validated
   training rows and the validation rows together, are within the noise of its own
   (``rivals``) make the verdict "indistinguishable" (none is named). A passing effect is named only if it shrinks the
   systematic part (``residuals.smooth_split``) of the systematic keypoints it claims (those
   whose unabsorbed signature correlates positively with the residuals): their summed mean
   square systematic part must fall and none may grow by more than its noise
   (``residuals.not_shrunk``), and must predict the file's validation rows better than the
   starting model (``cv.validation_score``, the noise-weighted MAE).
5. **Report** the named model as estimated after the decision (``fit.refine_estimate``: its
   strength profiled and every parameter refitted with the full step budget; then
   ``fit.prior_restart``, ``config.prior_start``: refitted from the starting material's own
   coefficients at that strength, the better fit kept, since the calibrated coefficients have
   absorbed part of the effect; the ranking keeps the fit that was tested), the residual
   tests before and after (``residuals``; a systematic residual left is "an unexplained
   residual"), the estimated noise floor and the share of the systematic residual explained,
   and the next samples (``proposal``) that best separate the leading models. The validation
   rows take no part in fitting or ranking; they veto a name and help tell the leader from its
   rivals.
"""
from __future__ import annotations

import time
from dataclasses import dataclass, field, replace

import numpy as np

from stitchswitch.errors import InvalidInputError
from stitchswitch.reduced.model.params import Material
from stitchswitch.validation.discovery.cv import (
    cross_validate,
    cross_validate_stepped,
    f_test,
    fold_labels,
    sign_flip_test,
    validation_score,
    within_noise,
)
from stitchswitch.validation.discovery.effects import LIBRARY, get_effect
from stitchswitch.validation.discovery.evaluate import Evaluator
from stitchswitch.validation.discovery.fit import (
    equal_footing,
    evaluated,
    fit,
    fit_effect,
    jacobian,
    prior_restart,
    refine_estimate,
)
from stitchswitch.validation.discovery.noise.proportional import (
    SIZE_FLOOR_MM,
    KeypointScale,
    ScaledEvaluator,
)
from stitchswitch.validation.discovery.noise.robust import winsorize
from stitchswitch.validation.discovery.residuals import residual_analysis
from stitchswitch.validation.discovery.signature import explain, signature
from stitchswitch.validation.discovery.space import BASE_FREE, ModelSpec
from stitchswitch.validation.measured import QUANTITIES, MeasuredData
from stitchswitch.validation.metrics import split_metrics

__all__ = ["DiscoveryConfig", "Candidate", "Discovery", "discover", "stage_count", "FORWARD_FITS",
           "lead_candidate", "rivals", "fold_refits", "screen_spec"]

#: Forward selection fits this many second effects: those whose unabsorbed signature (on top of
#: the first effect) correlates best with the residual the first one leaves. Fitting all five
#: others from two starts each was most of a run's cost when it ran (63 of 143 s CPU).
FORWARD_FITS = 2
#: How a full-resolution cross-validation moves each fold from the full fit
#: (``DiscoveryConfig.cv_method``).
CV_METHODS = ("refit", "stepped")


@dataclass(frozen=True)
class DiscoveryConfig:
    """Settings of the workflow. ``effects``: candidate names (None: the whole library).
    ``folds``: K of the cross-validation. ``alpha``: family-wise significance level.
    ``de_generations``: differential-evolution generations before the starting model's least
    squares (0: least squares from the starting material only), population ``de_popsize``.
    ``fit_max_nfev`` / ``cv_max_nfev``: least-squares steps of a full fit / of a fold refit;
    ``cv_radius``: how far (search units) a fold may move from the full fit in any
    coordinate (None: anywhere in the bounds). ``cv_method``: how the full-resolution
    cross-validation moves a fold: "stepped" (one damped step per fold, Marquardt damping
    ``cv_damping``, held-out designs warm-started from the full fit's equilibria:
    ``cv.cross_validate_stepped``) or "refit" (fold refits of ``cv_max_nfev`` evaluations,
    ``cv.cross_validate``). A stepped fold keeps the full fit only when its step is zero; a
    refit with one trial step often keeps it, its held-out rows then predicted in-sample
    (docs/discovery.md, "The stepped cross-validation").
    ``scan_points``: magnitudes of the strength scan. ``permutations``: of the residual test.
    ``screen_nodes``: the resolution (nodes) at which every candidate is screened (fitted with
    at most ``screen_max_nfev`` steps and cross-validated with one-step fold refits) before the
    ``refine`` best are polished (``polish_max_nfev`` steps) and cross-validated
    (``cv_max_nfev``) at the starting material's own resolution (None: no screening).
    ``propose``: how many next samples to propose. ``huber_c``: a robust fit (Huber's loss with
    threshold ``huber_c`` robust sigmas, ``discovery.robust``); None: least squares. ``forward``:
    when a named effect leaves a systematic residual, try a second effect (forward selection
    with the same rule, at alpha / (number of candidates left)). ``branches``: follow each
    training design's equilibrium along the strength scans and evaluate a bistable design on the
    branch nearest its measured row (``fit.follow_branches``); False: cold solves only.
    ``relative_noise``: the noise of a keypoint is proportional to its size (``relative_noise``:
    every keypoint, measured and predicted, is divided by its size relative to the mean, a
    smooth surface of the training rows' sizes; errors and the noise floor are then in mm at
    the mean size); False: one sigma per quantity.
    ``profile_points``: scanned strengths whose coefficients are refitted with the strength held
    (``fit.scan_effect``; 0: the one-step correction only). ``profile_leaders``: each leader
    polished at full resolution at a non-zero strength is profiled along its strength and
    refitted (``fit.refine_estimate``) before it is tested: a leader stopped short of its basin
    loses to a rival that happened to get closer to its own. ``prior_start``: the named
    effect's estimate is also refitted from the starting material's own coefficients at its
    estimated strength, and the better fit kept (``fit.prior_restart``): the calibrated
    starting model has absorbed part of the effect into its coefficients, and a fit from them
    can stay in that basin. Only the estimate: at the leaders, before the decision, the same
    restart also re-polishes the starting model (equal footing) and was measured to lose two
    half-identifications (docs/discovery.md, "Starting from the prior coefficients")."""

    effects: tuple | None = None
    folds: int = 5
    alpha: float = 0.05
    seed: int = 0
    de_generations: int = 0
    de_popsize: int = 6
    fit_max_nfev: int = 25
    cv_max_nfev: int = 2
    cv_radius: float | None = 1.0
    cv_method: str = "stepped"
    cv_damping: float = 0.1
    scan_points: int = 5
    permutations: int = 2000
    screen_nodes: int | None = 150
    screen_max_nfev: int = 12
    refine: int = 3
    polish_max_nfev: int = 4
    propose: int = 5
    huber_c: float | None = None
    relative_noise: bool = False
    forward: bool = True
    branches: bool = True
    profile_points: int = 0
    profile_leaders: bool = True
    prior_start: bool = True

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
        if int(self.profile_points) < 0:
            raise InvalidInputError(f"profile_points: {self.profile_points!r} must be >= 0")
        for name in ("folds", "fit_max_nfev", "cv_max_nfev", "scan_points", "permutations",
                     "refine", "polish_max_nfev", "propose", "screen_max_nfev"):
            if int(getattr(self, name)) < (2 if name == "folds" else 0 if name == "propose" else 1):
                raise InvalidInputError(f"{name}: {getattr(self, name)!r} is too small")
        if self.cv_method not in CV_METHODS:
            raise InvalidInputError(f"cv_method: {self.cv_method!r} is not one of "
                                    f"{', '.join(CV_METHODS)}")
        if not self.cv_damping > 0:
            raise InvalidInputError(f"cv_damping: {self.cv_damping!r} must be > 0")
        if self.cv_radius is not None and not self.cv_radius > 0:
            raise InvalidInputError(f"cv_radius: {self.cv_radius!r} must be > 0 (or None)")
        if self.screen_nodes is not None and int(self.screen_nodes) < 20:
            raise InvalidInputError(f"screen_nodes: {self.screen_nodes!r} is below 20")
        if self.huber_c is not None and not self.huber_c > 0:
            raise InvalidInputError(f"huber_c: {self.huber_c!r} must be > 0")
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
    resolution_nodes: int = 0
    refined: bool = True
    zero_strength: bool = False
    row_loss: np.ndarray | None = field(default=None, repr=False, compare=False)
    val_row_loss: np.ndarray | None = field(default=None, repr=False, compare=False)
    cv_folds: int = 0
    cv_stuck_folds: int = 0      # folds that kept the full fit's parameters exactly

    @property
    def held_out_loss(self) -> np.ndarray:
        """The loss of every row the fit did not see: the training rows' cross-validated
        losses, then the validation rows' (mean squared error over the five keypoints)."""
        parts = [a for a in (self.row_loss, self.val_row_loss) if a is not None]
        return np.concatenate(parts) if parts else np.zeros(0)

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
                "rank": self.rank, "resolution_nodes": self.resolution_nodes,
                "refined": self.refined, "zero_strength": self.zero_strength,
                "cv_folds": self.cv_folds, "cv_stuck_folds": self.cv_stuck_folds}


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
    return 5 + 2 * len(config.effects)


def _metrics(pred, measured) -> dict:
    full = split_metrics(pred, measured)
    return {q: {"mae_mm": full[q]["mae_mm"], "pct_error": full[q]["pct_error"]} for q in QUANTITIES}


def _start_fit(base, ev, designs, measured, start, config, executor):
    x0 = base.encode(base.start)
    if config.de_generations > 0:
        from stitchswitch.reduced.calibration.evolution import calibrate

        res = calibrate(designs, measured, base.start, maxiter=config.de_generations,
                        popsize=config.de_popsize, seed=config.seed, executor=executor,
                        free=base.free, check_identifiability=False)
        x0 = base.encode(res.material)
    return fit(base, ev, designs, measured, x0, max_nfev=config.fit_max_nfev)


def _refreshed(f, ev, designs, measured):
    """``f`` with its predictions re-evaluated (after designs gained branch states)."""
    return evaluated(f.spec, ev, designs, measured, f.x, f.evaluations, f.message)


def screen_spec(start: Material, nodes) -> ModelSpec:
    """The starting model at the screening resolution (``nodes``; None: ``start``'s own)."""
    from stitchswitch.reduced.calibration.evolution import search_material

    return ModelSpec(search_material(start, nodes) if nodes else start, None, BASE_FREE)


def _zero(spec, x) -> bool:
    """Is the effect of ``x`` at (numerically) zero strength: the starting model itself?"""
    values = spec.decode(x)[1].get(spec.effect, ())
    return all(abs(v) <= 1e-6 * p.probe for v, p in zip(values, spec.effect_parameters))


def _effect_values(spec, x, name: str) -> dict:
    """Effect ``name``'s parameter values in ``x``, by parameter name (zeros where ``spec``
    does not carry the effect)."""
    return dict(zip(spec.names[spec.offset:], spec.decode(x)[1].get(
        name, (0.0,) * len(spec.effect_parameters))))


def fold_refits(spec, ev, designs, measured, x, labels, config):
    """The full-resolution cross-validation of ``spec`` fitted at ``x``: with ``cv_method``
    "stepped", one damped step per fold (``cv_damping``) within the config's radius
    (``cv_radius``); with "refit", fold refits with the config's budget (``cv_max_nfev``)."""
    if config.cv_method == "stepped":
        return cross_validate_stepped(spec, ev, designs, measured, x, labels,
                                      damping=config.cv_damping, radius=config.cv_radius)
    return cross_validate(spec, ev, designs, measured, x, labels, max_nfev=config.cv_max_nfev,
                          radius=config.cv_radius)


def _candidate(name, spec, f, m_tr, cv, cv0, why, how, rss0, k0, m, config, ev, d_va, m_va,
               before_va, refined):
    """The ``Candidate`` of fit ``f`` (with its cross-validation ``cv``) against the starting
    model's RSS ``rss0`` and cross-validation ``cv0``."""
    n_res = m_tr.size
    rss1 = float(np.sum((f.predictions - m_tr) ** 2))
    F, p = f_test(rss0, rss1, n_res, k0, spec.size)
    zero = _zero(spec, f.x)
    pred_va = ev.one(spec, f.x, d_va)
    return Candidate(
        effect=name, cv_mse_mm2=cv.score_mm2, cv_improvement_mm2=cv0.score_mm2 - cv.score_mm2,
        cv_sign_flip_p=sign_flip_test(cv0.row_loss - cv.row_loss, seed=config.seed),
        train_mse_mm2=f.mse_mm2, f_statistic=F, p_value=p,
        significant=bool(refined and not zero and p < config.alpha / m
                         and cv.score_mm2 < cv0.score_mm2),
        n_parameters=spec.size, parameters=dict(f.parameters),
        effect_parameters=_effect_values(spec, f.x, name),
        val_mae_before_mm={q: v["mae_mm"] for q, v in
                           _metrics(ev.to_mm(d_va, before_va), ev.to_mm(d_va, m_va)).items()},
        val_mae_after_mm={q: v["mae_mm"] for q, v in
                          _metrics(ev.to_mm(d_va, pred_va), ev.to_mm(d_va, m_va)).items()},
        signature=why, uncertified_solves=f.uncertified, fit_start=how,
        spec=spec, x=f.x, resolution_nodes=spec.start.n_nodes, refined=refined,
        zero_strength=zero, row_loss=cv.row_loss, cv_folds=cv.folds,
        cv_stuck_folds=cv.stuck_folds,
        val_row_loss=np.mean((pred_va - np.asarray(m_va, dtype=float)) ** 2, axis=1)
        if len(d_va) else None)


def lead_candidate(ranking):
    """The candidate the decision is about: the best-ranked significant one, else the best
    ranked. Cross-validated errors a few percent apart do not order candidates reliably; a
    higher-ranked candidate that is not significant is then compared with it (``within_noise``)
    and, when the data cannot tell them apart, reported with it as indistinguishable instead of
    hiding a significant effect behind an insignificant one."""
    return next((c for c in ranking if c.significant), ranking[0])


def rivals(top, ranking, cv0_score_mm2: float, alpha: float, seed: int = 0) -> list:
    """The candidates reported with ``top`` as indistinguishable from it. A rival must itself
    explain the residual: refined, not at zero strength, a cross-validated error below the
    starting model's and an F test against it at level ``alpha`` (uncorrected: a rival need
    not survive the family-wise correction, but an effect that does not improve on the
    starting model at all explains nothing the data could confuse with ``top``); and its
    held-out losses must be within the noise of ``top``'s (``cv.within_noise``, paired over
    every held-out row: the training rows' cross-validated losses and the validation rows',
    twice the rows the training folds alone give)."""
    others = {c.effect: c.held_out_loss for c in ranking
              if c is not top and c.refined and not c.zero_strength
              and c.cv_mse_mm2 < cv0_score_mm2 and c.p_value < alpha}
    close = within_noise(top.held_out_loss, others, alpha, seed)
    return [c for c in ranking if c is not top and c.effect in close]


def _forward(first, first_screen, ev, d_tr, m_fit, labels, config, held_out=None) -> dict:
    """The best second effect after ``first`` (a refined ``Candidate``): the ``FORWARD_FITS``
    other effects whose unabsorbed signature correlates best with the residual left by
    ``first_screen`` (its screening-resolution fit) screened on top of it, the best one polished
    at full resolution and tested against the model with ``first`` re-polished on equal
    footing (F test at alpha / (number of candidates left), CV below it, non-zero). Each
    second effect is fitted from the better of its two starts. The test is checked before the
    re-polish (which can only lower the first model's RSS) and after it; a second effect that
    fails it is returned without cross-validations (``cv_mse_mm2`` None): the CV cannot make
    it pass. ``held_out``: (validation designs, their rows, noise sigma per keypoint); a second
    effect that passes must also predict them no worse than the model with ``first`` alone
    (``cv.validation_score``), the veto the first effect faces too."""
    from stitchswitch.validation.discovery.fit import Fit

    rss = lambda f: float(np.sum((f.predictions - m_fit) ** 2))      # noqa: E731
    base_c = first_screen.spec
    J = jacobian(base_c, ev, d_tr, first_screen.x, *base_c.bounds())
    residual = m_fit - first_screen.predictions
    sigs = {}
    for name in config.effects:
        if name != first.effect:
            sigs[name] = signature(base_c.then(name), ev, d_tr, first_screen.x)
    # only the effects whose unabsorbed signature best matches what is left are fitted
    corr = {name: abs(explain(J, sig, residual, QUANTITIES)["correlation"])
            for name, sig in sigs.items()}
    chosen = sorted(sigs, key=lambda n: (-corr[n], n))[:FORWARD_FITS]
    best = None
    for name in chosen:
        spec = base_c.then(name)
        sig = sigs[name]
        f, _ = fit_effect(spec, ev, d_tr, m_fit, first_screen, J, sig,
                          max_nfev=config.screen_max_nfev, scan_points=config.scan_points + 2,
                          profile=config.profile_points)
        cv = cross_validate(spec, ev, d_tr, m_fit, f.x, labels, max_nfev=1)
        if best is None or cv.score_mm2 < best[2]:
            best = (name, f, cv.score_mm2)
    name, fc, _ = best
    base_f = first.spec
    pred_a = ev.one(base_f, first.x, d_tr)
    fit_a = Fit(base_f, first.x, pred_a, float(np.mean((pred_a - m_fit) ** 2)), 0, 0, "first")
    spec_f = base_f.then(name)
    ff = fit(spec_f, ev, d_tr, m_fit, fc.x, max_nfev=config.polish_max_nfev)
    m_left = len(config.effects) - 1
    threshold = config.alpha / m_left
    passes = lambda r0, f: f_test(r0, rss(f), m_fit.size, base_f.size, f.spec.size)[1] < threshold  # noqa: E731
    zero = _zero(spec_f, ff.x)
    out = {"effect": name, "after": first.effect, "threshold": threshold, "zero_strength": zero,
           "parameters": spec_f.describe(ff.x), "spec": spec_f, "x": ff.x}
    rejected = {"cv_mse_mm2": None, "cv_mse_first_only_mm2": None, "validation_score": None,
                "validation_score_first_only": None, "significant": False, "vetoed": False}
    if zero or not passes(rss(fit_a), ff):
        # cannot pass: the equal-footing re-polish only lowers the first model's RSS, so the
        # test fails whatever the cross-validations say; they are not run
        F, p = f_test(rss(fit_a), rss(ff), m_fit.size, base_f.size, spec_f.size)
        return {**out, "f_statistic": F, "p_value": p, **rejected}
    fit_a, _ = equal_footing(base_f, ev, d_tr, m_fit, fit_a, {name: ff}, passes,
                             max_nfev=config.fit_max_nfev,
                             screen_spec=base_c if base_c != base_f else None,
                             polish_max_nfev=config.polish_max_nfev)
    F, p = f_test(rss(fit_a), rss(ff), m_fit.size, base_f.size, spec_f.size)
    if p >= threshold:
        return {**out, "f_statistic": F, "p_value": p, **rejected}
    cv_a = fold_refits(base_f, ev, d_tr, m_fit, fit_a.x, labels, config)
    cv_f = fold_refits(spec_f, ev, d_tr, m_fit, ff.x, labels, config)
    scores = None
    if held_out is not None and len(held_out[0]):
        d_va, m_va, sigma = held_out
        scores = (validation_score(ev.one(base_f, first.x, d_va), m_va, sigma),
                  validation_score(ev.one(spec_f, ff.x, d_va), m_va, sigma))
    cv_better = cv_f.score_mm2 < cv_a.score_mm2
    vetoed = bool(cv_better and scores is not None and scores[1] > scores[0])
    return {**out, "f_statistic": F, "p_value": p, "cv_mse_mm2": cv_f.score_mm2,
            "cv_mse_first_only_mm2": cv_a.score_mm2,
            "validation_score": None if scores is None else scores[1],
            "validation_score_first_only": None if scores is None else scores[0],
            "significant": bool(cv_better and not vetoed), "vetoed": vetoed}


def discover(data: MeasuredData, start: Material, config: DiscoveryConfig = DiscoveryConfig(), *,
             executor=None, progress=None, start_label: str = "default") -> Discovery:
    """Run the workflow on ``data`` from the starting material ``start``; see the module
    docstring. ``executor``: a map-like for parallel solves. ``progress(message, stage,
    total)`` is called as each stage starts."""
    from stitchswitch.validation.discovery.proposal import (
        design_grid,
        model_view,
        propose,
        reachable,
    )
    from stitchswitch.validation.discovery.residuals import not_shrunk, smooth_split

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
    measured = measured_mm = data.keypoints()
    tr, va = split == "train", split == "val"
    designs = [(float(d), float(p)) for d, p in zip(d_all, p_all)]
    d_tr = [x for x, t in zip(designs, tr) if t]
    d_va = [x for x, t in zip(designs, va) if t]
    m_tr, m_va = measured[tr], measured[va]
    train_rows = [r for r, t in zip(rows, tr) if t]
    n_res = m_tr.size
    ev = Evaluator(executor, targets=dict(zip(d_tr, m_tr)) if config.branches else None)
    sizes = None
    if config.relative_noise:
        # from here on every keypoint is size-scaled (``relative_noise``); the results are
        # converted back to mm where they are reported
        sizes = KeypointScale.from_rows(d_tr, m_tr)
        ev = ScaledEvaluator(ev, sizes)
        measured = measured / sizes(designs)
        m_tr, m_va = measured[tr], measured[va]
    base = ModelSpec(start, None, BASE_FREE)
    screen = screen_spec(start, config.screen_nodes)
    lo, hi = base.bounds()
    labels = fold_labels(d_tr, config.folds, config.seed)
    m = len(config.effects)
    threshold = config.alpha / m

    # 1. the starting model, calibrated: searched at the screening resolution, polished
    step("calibrating the starting model")
    fs = _start_fit(screen, ev, d_tr, m_tr, start, config, executor)
    m_fit, weights = m_tr, np.ones_like(m_tr)
    if config.huber_c:
        for _ in range(3):          # alternate clipping and refitting (converges to Huber's fit)
            m_fit, weights, _scale = winsorize(m_tr, fs.predictions, config.huber_c)
            fs = fit(screen, ev, d_tr, m_fit, fs.x, max_nfev=config.polish_max_nfev)
    fb = fit(base, ev, d_tr, m_fit, fs.x, max_nfev=config.polish_max_nfev) if screen != base else fs

    # 2-3. screening: every candidate's signature, refit and cross-validation at the screening
    # resolution, from the screened starting model
    step("screening: the starting model's Jacobian and cross-validation")
    J0s = jacobian(screen, ev, d_tr, fs.x, lo, hi)
    cv0s = cross_validate(screen, ev, d_tr, m_fit, fs.x, labels, max_nfev=1)
    rss0s = float(np.sum((fs.predictions - m_fit) ** 2))
    before_va_s = ev.one(screen, fs.x, d_va)
    screened, sigs, screened_fit = {}, {}, {}
    for name in config.effects:
        spec = screen.with_effect(name)
        step(f"{name}: signature and refit")
        sig = signature(spec, ev, designs, fs.x)
        why = explain(J0s, sig[tr], m_fit - fs.predictions, QUANTITIES)
        sigs[name] = {"per_unit": sig, "pattern": why.pop("pattern")}
        f, how = fit_effect(spec, ev, d_tr, m_fit, fs, J0s, sig[tr],
                            max_nfev=config.screen_max_nfev, scan_points=config.scan_points,
                            profile=config.profile_points)
        step(f"{name}: cross-validation")
        cv = cross_validate(spec, ev, d_tr, m_fit, f.x, labels, max_nfev=1)
        screened[name] = _candidate(name, spec, f, m_fit, cv, cv0s, why, how["start"], rss0s,
                                    base.size, m, config, ev, d_va, m_va, before_va_s,
                                    refined=screen == base)
        screened_fit[name] = f
    order = sorted(screened.values(), key=lambda c: (c.cv_mse_mm2, c.n_parameters, c.effect))
    leaders = [c.effect for c in order[:config.refine]]

    # 4. the leaders at full resolution; the starting model re-polished from every start an
    # apparently significant leader had, so that both sides of the test are fitted equally well
    step("refining the leading candidates at full resolution")
    if ev.branches:
        # designs that gained branch states are now evaluated on the branch nearest their
        # row, for the starting model too: its fit is re-evaluated so that both sides of
        # every comparison see the same branches
        fb = _refreshed(fb, ev, d_tr, m_fit)
    refined_fits = {}
    for name in leaders:
        spec = base.with_effect(name)
        if screen != base:
            f = fit(spec, ev, d_tr, m_fit, screened_fit[name].x, max_nfev=config.polish_max_nfev)
            if config.profile_leaders and not _zero(spec, f.x):
                f, _ = refine_estimate(f, ev, d_tr, m_fit, max_nfev=config.polish_max_nfev)
        else:
            f = _refreshed(screened_fit[name], ev, d_tr, m_fit)
        refined_fits[name] = f
    def passes(rss0, f):
        rss1 = float(np.sum((f.predictions - m_fit) ** 2))
        return f_test(rss0, rss1, n_res, base.size, f.spec.size)[1] < threshold

    base_fit, repolished = equal_footing(base, ev, d_tr, m_fit, fb, refined_fits, passes,
                                         max_nfev=config.fit_max_nfev,
                                         screen_spec=screen if screen != base else None,
                                         polish_max_nfev=config.polish_max_nfev)
    rss0 = float(np.sum((base_fit.predictions - m_fit) ** 2))
    cv0 = fold_refits(base, ev, d_tr, m_fit, base_fit.x, labels, config)
    before = np.empty_like(measured)
    before[tr] = base_fit.predictions
    before[va] = ev.one(base, base_fit.x, d_va)
    final = {}
    for name in leaders:
        f = refined_fits[name]
        if f.mse_mm2 > base_fit.mse_mm2:      # the effect cannot beat the starting model
            x0 = f.spec.extend(base_fit.x, (0.0,) * len(f.spec.effect_parameters))
            f = evaluated(f.spec, ev, d_tr, m_fit, x0, f.evaluations,
                          "no improvement over the starting model")
        # a leader at zero strength is the starting model itself: it cannot pass, and its
        # held-out error is the starting model's (no fold refits run for it)
        cvr = cv0 if _zero(f.spec, f.x) else fold_refits(f.spec, ev, d_tr, m_fit, f.x,
                                                         labels, config)
        c = screened[name]
        final[name] = _candidate(name, f.spec, f, m_fit, cvr, cv0, c.signature,
                                 c.fit_start, rss0, base.size, m, config, ev, d_va, m_va,
                                 before[va], refined=True)
    rest = [replace(c, significant=False, refined=False) for c in order[config.refine:]]
    full = sorted(final.values(), key=lambda c: (c.cv_mse_mm2, c.n_parameters, c.effect))
    ranking = tuple(replace(c, rank=rank) for rank, c in enumerate(full + rest, start=1))

    # 5. decide: named, indistinguishable, or none; the claims and what is left
    step("decision, the validation gap and the next samples")
    res0_tr = m_tr - base_fit.predictions
    split0 = smooth_split(d_all[tr], p_all[tr], res0_tr)
    res_before = residual_analysis(d_all, p_all, measured - before, QUANTITIES,
                                   alpha=config.alpha, permutations=config.permutations,
                                   seed=config.seed)
    top = lead_candidate(ranking)
    group = []
    if top.significant:
        group = [top] + rivals(top, ranking, cv0.score_mm2, config.alpha, config.seed)
    chosen = top if top.significant else None
    e0 = sum(split0["systematic_energy_mm2"])

    def with_model(spec, x):
        """(predictions of every row, smooth split and residual analysis of the training
        residuals, the quantities still systematic, the share of the systematic residual
        explained) with the model ``spec`` at ``x``; the starting model's for None."""
        pred = before.copy()
        if spec is not None:
            pred[tr] = ev.one(spec, x, d_tr)
            pred[va] = ev.one(spec, x, d_va)
        sp = smooth_split(d_all[tr], p_all[tr], m_tr - pred[tr])
        res = residual_analysis(d_all, p_all, measured - pred, QUANTITIES, alpha=config.alpha,
                                permutations=config.permutations, seed=config.seed)
        e1 = sum(sp["systematic_energy_mm2"])
        return (pred, sp, res, [q for q in QUANTITIES if res[q]["systematic"]],
                (1.0 - e1 / e0) if e0 > 0 else None)

    after, split1, res_after, left, explained = with_model(
        *((chosen.spec, chosen.x) if chosen else (None, None)))
    systematic_before = [q for q in QUANTITIES if res_before[q]["systematic"]]
    claims, unshrunk = [], []
    if chosen:
        per_q = chosen.signature["per_quantity"]
        claims = [q for q in systematic_before if per_q[q] > 0] or systematic_before
        k_of = {q: k for k, q in enumerate(QUANTITIES)}
        unshrunk = [QUANTITIES[k] for k in not_shrunk(split0, split1, [k_of[q] for q in claims])]
    names = [c.effect for c in group]
    held_out = (validation_score(before[va], m_va, split0["noise_sigma_mm"]),
                validation_score(after[va], m_va, split0["noise_sigma_mm"]))
    worse_held_out = bool(va.any()) and held_out[1] > held_out[0]
    if chosen and unshrunk:
        verdict = "none"
        reason = (f"{top.effect} lowers the cross-validated error and its improvement is "
                  f"significant (p = {top.p_value:.2g} < {threshold:.2g}), but it does not "
                  f"shrink the systematic residual of {', '.join(unshrunk)}, which it claims "
                  "to explain: no effect is named")
    elif chosen and len(group) > 1:
        verdict = "indistinguishable"
        reason = (f"{', '.join(names)} explain the residual about equally: their cross-validated "
                  f"errors ({', '.join(f'{c.cv_mse_mm2:.3f}' for c in group)} mm^2) are within "
                  f"the noise of one another (sign-flip test of the per-row held-out losses, "
                  f"cross-validated and validation rows, p >= {config.alpha:g}; each improves "
                  f"on the starting model at p < {config.alpha:g}); the data cannot tell them "
                  "apart (the proposed samples below would)")
    elif chosen and worse_held_out:
        verdict = "none"
        reason = (f"{top.effect} lowers the cross-validated error ({top.cv_mse_mm2:.3f} against "
                  f"{cv0.score_mm2:.3f} mm^2) and its improvement is significant (p = "
                  f"{top.p_value:.2g} < {threshold:.2g}), but it predicts the validation rows "
                  f"worse than the starting model (noise-weighted MAE {held_out[0]:.2f} -> "
                  f"{held_out[1]:.2f}): it fits the training rows as a stand-in, not as the "
                  "missing physics; no effect is named")
    elif chosen:
        verdict = "named"
        best = ("has the lowest cross-validated error" if top is ranking[0] else
                "is the best-ranked candidate whose improvement is significant, with a "
                "cross-validated error")
        reason = (f"{top.effect} {best} ({top.cv_mse_mm2:.3f} "
                  f"against {cv0.score_mm2:.3f} mm^2 for the starting model) and its improvement "
                  f"is significant against the starting model fitted equally well: "
                  f"F = {top.f_statistic:.1f}, p = {top.p_value:.2g} < {threshold:.2g} "
                  f"(alpha {config.alpha:g} / {m} candidates)")
    elif top.zero_strength:
        verdict = "none"
        reason = (f"the best candidate, {top.effect}, is fitted at zero strength: it is the "
                  "starting model itself")
    elif top.cv_mse_mm2 >= cv0.score_mm2:
        verdict = "none"
        reason = (f"no candidate lowers the cross-validated error of the starting model "
                  f"({cv0.score_mm2:.3f} mm^2; best {top.effect} {top.cv_mse_mm2:.3f})")
    else:
        verdict = "none"
        reason = (f"the best candidate, {top.effect}, lowers the cross-validated error "
                  f"({top.cv_mse_mm2:.3f} against {cv0.score_mm2:.3f} mm^2) but not "
                  f"significantly against the starting model fitted equally well: "
                  f"p = {top.p_value:.2g} >= {threshold:.2g}")
    estimate = None
    if verdict == "named":
        # the decision is made; what is reported and predicted is the best estimate of the
        # named model (its strength profiled, every parameter refitted, and refitted from the
        # starting material's own coefficients)
        tested = evaluated(chosen.spec, ev, d_tr, m_fit, chosen.x, 0, "decided")
        best, estimate = refine_estimate(tested, ev, d_tr, m_fit, max_nfev=config.fit_max_nfev)
        if config.prior_start:
            best, estimate["prior_start"] = prior_restart(
                best, ev, d_tr, m_fit, max_nfev=config.screen_max_nfev,
                polish_max_nfev=config.polish_max_nfev,
                screen_spec=replace(best.spec, start=screen.start))
            estimate["train_mse_mm2"] = best.mse_mm2
        estimate["effect_parameters"] = _effect_values(best.spec, best.x, chosen.effect)
        estimate["parameters"] = dict(best.parameters)
        after, split1, res_after, left, explained = with_model(chosen.spec, best.x)
    second = None
    if verdict == "named" and left and config.forward and len(config.effects) > 1:
        step(f"forward selection: a second effect after {chosen.effect}")
        second = _forward(chosen, screened_fit[chosen.effect], ev, d_tr, m_fit, labels, config,
                          held_out=(d_va, m_va, split0["noise_sigma_mm"]))
        if second["significant"]:
            after, split1, res_after, left, explained = with_model(second["spec"], second["x"])
            reason += (f"; forward selection adds {second['effect']} (p = {second['p_value']:.2g}"
                       f" < {second['threshold']:.2g} against the model with {chosen.effect})")
        elif second["vetoed"]:
            reason += (f"; forward selection: {second['effect']} passes the F test (p = "
                       f"{second['p_value']:.2g}) and the cross-validation but predicts the "
                       f"validation rows worse (noise-weighted MAE "
                       f"{second['validation_score_first_only']:.2f} -> "
                       f"{second['validation_score']:.2f}): not added")
        else:
            reason += (f"; forward selection: no significant second effect (best "
                       f"{second['effect']}, p = {second['p_value']:.2g})")
    if verdict != "named" and verdict != "indistinguishable":
        chosen = None
        after = before.copy()
        res_after, split1, left, explained = res_before, split0, list(systematic_before), 0.0
    # the next samples: what separates the leading models
    lead = group if len(group) > 1 else [c for c in ranking if c.refined
                                         and not c.zero_strength][:2]
    models = [("starting model", base, base_fit.x)] * (len(group) <= 1)
    models = list(models) + [(c.effect, c.spec, c.x) for c in lead]
    grid = design_grid()
    sigma = split0["noise_sigma_mm"]
    views = {label: model_view(ev, spec, x, grid, d_tr, sigma,
                               replace(spec, start=screen.start))
             for label, spec, x in models} if config.propose else {}
    reach = reachable(ev, models, grid) if config.propose else None
    proposal = propose(views, grid, sigma, config.propose, reach)
    summary = {
        "missing_effect": chosen.effect if verdict == "named" else None,
        "missing_effects": ([chosen.effect] + ([second["effect"]] if second and
                                               second["significant"] else []))
        if verdict == "named" else [],
        "forward": None if second is None else {
            k: v for k, v in second.items() if k not in ("spec", "x")},
        "verdict": verdict,
        "significant": verdict == "named",
        "indistinguishable": names if verdict == "indistinguishable" else [],
        "effect_parameters": dict(estimate["effect_parameters"]) if estimate else {},
        "estimate": estimate,
        "after_model": chosen.effect if chosen else None,
        "decision": reason,
        "ranking": [c.as_dict() for c in ranking],
        "before": _metrics(ev.to_mm(d_va, before[va]), ev.to_mm(d_va, m_va)),
        "after": _metrics(ev.to_mm(d_va, after[va]), ev.to_mm(d_va, m_va)),
        "starting_model": {
            "label": start_label, "free": list(base.free),
            "parameters": base_fit.parameters, "train_mse_mm2": base_fit.mse_mm2,
            "cv_score_mm2": cv0.score_mm2, "cv_folds": cv0.folds,
            "cv_stuck_folds": cv0.stuck_folds, "uncertified_solves": base_fit.uncertified,
            "screened_train_mse_mm2": fs.mse_mm2, "repolished": repolished},
        "residuals_before": res_before,
        "residuals_after": res_after,
        "claims": {"keypoints": claims, "not_shrunk": unshrunk},
        "validation_score": {"before": held_out[0] if va.any() else None,
                             "after": held_out[1] if va.any() else None,
                             "how": "sum over keypoints of the validation MAE / noise sigma"},
        "robust": {"huber_c": config.huber_c, "down_weighted": [
            {"sample": train_rows[i].label, "quantity": QUANTITIES[k],
             "weight": float(weights[i, k])}
            for i, k in zip(*np.nonzero(weights < 1.0))]},
        "unexplained_residual": left,
        "noise_floor": {"sigma_mm": dict(zip(QUANTITIES, sigma)),
                        "how": "residual standard error of a quadratic surface in (d, p) fitted "
                               "to the starting model's training residuals (no replicates)"
                               + ("; the residuals divided by the keypoint's size relative to "
                                  "the mean: sigma at the mean size, proportional to the size"
                                  if sizes else "")},
        "relative_noise": None if sizes is None else {
            "mean_size_mm": dict(zip(QUANTITIES, sizes.mean_mm.tolist())),
            "size_floor_mm": SIZE_FLOOR_MM},
        "systematic": {"before_rms_mm": dict(zip(QUANTITIES, split0["systematic_rms_mm"])),
                       "after_rms_mm": dict(zip(QUANTITIES, split1["systematic_rms_mm"])),
                       "share_explained": explained},
        "proposal": proposal,
        "branch_designs": [{"d_mm": d, "fill": p, "found_by": [name for name, _ in states]}
                           for (d, p), states in sorted(ev.branches.items())],
        "significance_threshold": threshold,
        "n_train": int(tr.sum()), "n_val": int(va.sum()),
        "config": config.as_dict(),
    }
    return Discovery(summary=summary, ranking=ranking, diameter_mm=d_all, fill=p_all, split=split,
                     measured=measured_mm, before=ev.to_mm(designs, before),
                     after=ev.to_mm(designs, after), signatures=sigs,
                     elapsed_s=time.perf_counter() - t0, solves=ev.calls)
