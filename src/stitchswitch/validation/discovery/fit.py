"""Fitting a model (the starting one, or it plus one effect) to training keypoints.

Objective: the paper's, the mean squared error (mm^2) over h, r_a, z_a, r_b, z_b of the rows
fitted (``reduced.calibration.evolution``). Method: a bounded trust-region least-squares solver
(``scipy.optimize.least_squares``, method "trf") whose Jacobian is a forward finite difference
through the cached ``Evaluator``, warm-started from the centre (steps
``discovery_space.BASE_STEP`` / ``EFFECT_STEP``; a step that would leave the bounds is taken
backwards). Local, so it needs a good start:

* the starting model: optionally a short differential evolution over the free coefficients
  (``reduced.calibration.evolution.calibrate``), then least squares;
* with an effect (``fit_effect``): two starts, the one with the lower misfit refined by least
  squares: a one-dimensional scan of the effect's strength with the starting model's fitted
  coefficients (``scan_values``: geometric steps from the probe value to the bound, each sign
  for a signed parameter), each point also corrected by one Gauss-Newton step of the
  coefficients with the starting model's Jacobian, and optionally (``profile``) at the best
  strengths from the probe outward a true profile point (the coefficients refitted by least squares with the
  strength held: far from the start that one-Jacobian correction misjudges the strength the
  data prefer), and the linearized joint step (``linearized_start``: one
  Gauss-Newton step in the coefficients and the strength together, from the starting model's
  Jacobian and the effect's signature). The misfit along the strength can have two basins
  (``boundary_transition`` at 11 mm: minima of the scan near 2 and 8 mm, 0.6 % apart, whose
  refinements end at 2.2 mm and 10.2 mm, 3.5 % apart): a second local minimum of the scanned
  profile within ``SECOND_BASIN`` of the best start's misfit is refined too, and the better
  fit kept. If the refined fit is still worse than the starting model, the effect at zero
  strength (exactly the starting model) is the result.

``equal_footing``: a nested comparison is fair only if both models are fitted equally well. An
extended fit starts from the starting model's coefficients and may walk to a better optimum of
the *coefficients* alone (at zero strength it is the starting model). So the starting model is
re-polished from the coefficients of every extended fit that would pass the test, and the best
starting-model fit found is the one the test compares with.

``prior_restart``: the other way round, the starting model calibrated on data that carry the
missing effect has absorbed what its coefficients can of it, and an extended fit from those
coefficients can stay in their basin; the named effect's estimate is also refitted from the
starting material's own coefficients at its strength, and the better fit kept.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["Fit", "fit", "trust_box", "evaluated", "jacobian", "scan_values", "scan_effect", "second_basin",
           "linearized_start", "fit_effect", "equal_footing", "follow_branches", "SECOND_BASIN",
           "prior_restart", "walked",
           "BRANCH_MM", "BRANCH_SHARE", "BELOW_PROBE", "PROFILE_NFEV", "refine_estimate",
           "ESTIMATE_FACTORS"]

#: A second local minimum of the scanned strength profile is refined when its misfit is within
#: this fraction of the best start's.
SECOND_BASIN = 0.02
#: An equilibrium followed along the strength scan is another branch than the evaluator's
#: value at the same parameters when some keypoint differs by more than this (mm).
BRANCH_MM = 2.0
#: ... and it is kept only when it at least halves the design's squared error there: a jump to
#: the other branch of a bistable design misses its row by several mm.
BRANCH_SHARE = 0.5
#: The strength scan also visits these fractions of the probe value: a weak effect below the
#: probe (a weak hoop bending, a weak negative natural curvature, where the curled branch
#: already fits the bistable designs) had no scanned point near it.
BELOW_PROBE = (0.2, 0.5)
#: The profile (``scan_effect(..., profile=n)``, ``DiscoveryConfig.profile_points``): at the
#: n best scanned strengths from the probe outward (where the starting model's Jacobian J0 is
#: a poor guide), the coefficients are refitted by least squares with the strength held, with
#: at most ``PROFILE_NFEV`` function evaluations. Off (0) by default: measured on the
#: benchmark, 2 profile points named fill_exponent on null data (a false discovery).
PROFILE_NFEV = 3
#: ``refine_estimate`` profiles a named effect's strength at these multiples of its fitted
#: value: the fits that decide start at zero strength with a few steps each and tend to stop
#: short of the strength the data prefer (docs/discovery.md, "The estimate").
ESTIMATE_FACTORS = (0.6, 0.8, 1.25, 1.6, 2.0)


@dataclass(frozen=True)
class Fit:
    """A fitted model: ``spec`` and its search vector ``x``; ``predictions`` (n, 5) on the
    fitted designs; ``mse_mm2`` their mean squared error; ``uncertified`` solves among them."""

    spec: object
    x: np.ndarray
    predictions: np.ndarray
    mse_mm2: float
    evaluations: int
    uncertified: int
    message: str

    @property
    def parameters(self) -> dict:
        return self.spec.describe(self.x)


def jacobian(spec, ev, designs, x, lo, hi, columns: int | None = None):
    """Forward-difference Jacobian (5 n, k) of the keypoints of ``designs`` at ``x``; with
    ``columns``, only the derivatives by the first ``columns`` coordinates."""
    steps = spec.steps()[:columns]
    xs, signed = [np.asarray(x, dtype=float)], []
    for k, h in enumerate(steps):
        xk = xs[0].copy()
        h = h if xk[k] + h <= hi[k] else -h
        xk[k] += h
        xs.append(xk)
        signed.append(h)
    centre = ev.one(spec, xs[0], designs)
    preds = ev.perturbed(spec, xs[0], xs[1:], designs)
    return np.stack([(preds[k] - centre).ravel() / h for k, h in enumerate(signed)], axis=1)


def trust_box(spec, x0, radius: float | None = None):
    """(``x0`` clipped into ``spec``'s bounds, (lo, hi) the bounds, (lo, hi) of the box within
    ``radius`` of it in every coordinate, inside the bounds; the bounds with no radius)."""
    lo, hi = spec.bounds()
    x0 = np.clip(np.asarray(x0, dtype=float), lo, hi)
    if radius is None:
        return x0, (lo, hi), (lo, hi)
    return x0, (lo, hi), (np.maximum(lo, x0 - radius), np.minimum(hi, x0 + radius))


def fit(spec, ev, designs, measured, x0, *, max_nfev: int = 20, free: int | None = None,
        radius: float | None = None) -> Fit:
    """Least squares from ``x0`` (clipped into the bounds) with at most ``max_nfev`` steps; with
    ``free``, only the first ``free`` coordinates move (the rest, the candidate's strength in
    a profile, stay at ``x0``'s); with ``radius``, every coordinate stays within ``radius``
    (search units: log10 of a coefficient, probes of an effect) of ``x0``'s."""
    from scipy.optimize import least_squares

    measured = np.asarray(measured, dtype=float)
    x0, (lo, hi), (box_lo, box_hi) = trust_box(spec, x0, radius)
    k = len(x0) if free is None else int(free)
    whole = lambda y: np.concatenate([y, x0[k:]])                      # noqa: E731
    calls = [0]

    def fun(y):
        calls[0] += 1
        return (ev.one(spec, whole(y), designs) - measured).ravel()

    def jac(y):
        # once the evaluations are used up, scipy still differentiates at the point it then
        # stops at (x0 itself when max_nfev is 1), for a gradient test only: no step uses it,
        # so zeros stand in for the 5 n solves of a finite difference
        if calls[0] >= max_nfev:
            return np.zeros((measured.size, k))
        return jacobian(spec, ev, designs, whole(y), lo, hi, columns=k)

    res = least_squares(fun, x0[:k], jac=jac, bounds=(box_lo[:k], box_hi[:k]), method="trf",
                        max_nfev=max_nfev, x_scale=1.0, xtol=1e-5, ftol=1e-6, gtol=1e-8)
    x = whole(np.asarray(res.x, dtype=float))
    # the best point evaluated is the result (trf may end on a rejected trial)
    pred = ev.one(spec, x, designs)
    mse = float(np.mean((pred - measured) ** 2))
    p0 = ev.one(spec, x0, designs)
    if float(np.mean((p0 - measured) ** 2)) < mse:
        x, pred, mse = x0, p0, float(np.mean((p0 - measured) ** 2))
    return Fit(spec, x, pred, mse, int(res.nfev), ev.n_uncertified(spec, x, designs),
               str(res.message))


def evaluated(spec, ev, designs, measured, x, evaluations: int, message: str) -> Fit:
    """The ``Fit`` of ``spec`` at ``x`` as the evaluator predicts it now (a design that has
    gained branch states since is evaluated on them)."""
    pred = ev.one(spec, x, designs)
    return Fit(spec, x, pred, float(np.mean((pred - measured) ** 2)), evaluations,
               ev.n_uncertified(spec, x, designs), message)


def scan_values(spec, points: int = 5) -> list[tuple]:
    """Effect values scanned before the fit: the first parameter at zero, at ``BELOW_PROBE``
    fractions of its probe and at ``points`` geometric steps from its probe to its bound (both
    signs if signed); others at their probe."""
    params = spec.effect_parameters
    first = params[0]
    mags = np.concatenate([first.probe * np.asarray(BELOW_PROBE),
                           np.geomspace(first.probe, max(first.upper, -first.lower), points)])
    values = [0.0] + [m for m in mags if m <= first.upper]
    if first.signed:
        values += [-m for m in mags if -m >= first.lower]
    rest = tuple(p.probe for p in params[1:])
    return [(v,) + rest for v in values]


def scan_effect(spec, ev, designs, measured, x_base, points: int = 5, J0=None,
                profile: int = 0):
    """(best x, [(values, mse)]) of the strength scan from the coefficients of ``x_base``.

    With the starting model's Jacobian ``J0`` every scanned strength also gets one Gauss-Newton
    correction of the coefficients (the coefficients partly re-adapt to the strength, which a
    large effect needs to be recognized at all), and the ``profile`` best strengths at or above
    the probe (by the better of those two points) a least-squares refit of the coefficients
    with the strength held (``PROFILE_NFEV`` evaluations): the profile itself where J0, taken
    at zero strength, is a poor guide. The best point of each strength counts."""
    measured = np.asarray(measured, dtype=float)
    xs = [spec.extend(x_base, v) for v in scan_values(spec, points)]
    follow_branches(spec, ev, designs, xs)     # the scan is then evaluated on the branches found
    preds = ev.keypoints(spec, xs, designs)
    k = spec.offset
    if J0 is not None:
        lo, hi = spec.bounds()
        corrected = []
        for x, p in zip(xs, preds):
            dx = np.linalg.lstsq(J0, (measured - p).ravel(), rcond=None)[0]
            xc = x.copy()
            xc[:k] = np.clip(x[:k] + dx, lo[:k], hi[:k])
            corrected.append(xc)
        xs = xs + corrected
        preds = preds + ev.keypoints(spec, corrected, designs)
    mse = [float(np.mean((p - measured) ** 2)) for p in preds]
    if J0 is not None and profile:
        # the true profile where J0 is poorest: at the best scanned strengths from the probe
        # outward (x holds the strength in probe units), the coefficients refitted with the
        # strength held
        at = {}
        for j, x in enumerate(xs):
            v = float(x[k])
            if abs(v) >= 1.0 - 1e-12 and (v not in at or mse[j] < mse[at[v]]):
                at[v] = j
        for j in sorted(at.values(), key=lambda j: (mse[j], abs(float(xs[j][k]))))[:profile]:
            f = fit(spec, ev, designs, measured, xs[j], max_nfev=PROFILE_NFEV, free=k)
            xs.append(f.x)
            mse.append(f.mse_mm2)
    table = [(spec.decode(x)[1][spec.effect], m) for x, m in zip(xs, mse)]
    nonzero = [j for j in range(len(xs)) if np.any(xs[j][k:] != 0)]
    best = min(nonzero, key=lambda j: mse[j])
    floor = spec.effect_parameters[0].probe
    return xs[best], table, [xs[j] for j in second_basin(table, floor)]


def follow_branches(spec, ev, designs, xs) -> int:
    """Continue every design's equilibrium along the scan ``xs`` (the candidate's first
    parameter varies; one path per sign outward from zero, one inward from the bound to zero)
    and give a design, as a branch state (``Evaluator.add_branch``), the followed equilibrium
    nearest its target among those that differ from the evaluator's value at the same x by
    more than ``BRANCH_MM`` (some keypoint) and are nearer the target than that value (squared
    error over the five keypoints, mm^2: at most ``BRANCH_SHARE`` of it, and ``BRANCH_MM``^2
    less). Both kinds matter: the
    curled branch a strong negative curvature leads to, and the popped branch continued from
    zero where the cold solve at a weak curvature already curls. Returns the number of states
    added (0 when the evaluator has no targets, i.e. branch following is off)."""
    rows = [ev.targets.get((float(d[0]), float(d[1]))) for d in designs]
    if not any(r is not None for r in rows):
        return 0
    k = spec.offset
    zero = [x for x in xs if not np.any(x[k:])][:1]
    err = lambda kp, j: float(np.sum((kp[j] - rows[j]) ** 2))      # noqa: E731
    best = {}
    for sign in (1.0, -1.0):
        side = sorted((x for x in xs if x[k] * sign > 0), key=lambda x: abs(x[k]))
        if not side:
            continue
        for path in (zero + side, side[::-1] + zero):
            for x, (kp, states) in zip(path, ev.continued(spec, path, designs)):
                now = ev.one(spec, x, designs)
                for j, row in enumerate(rows):
                    if row is None or np.max(np.abs(kp[j] - now[j])) <= BRANCH_MM:
                        continue
                    e, e_now = err(kp, j), err(now, j)
                    if (e < min(BRANCH_SHARE * e_now, e_now - BRANCH_MM ** 2)
                            and (j not in best or e < best[j][0])):
                        best[j] = (e, states[j])
    return sum(ev.add_branch(designs[j], state, spec.effect)
               for j, (_, state) in sorted(best.items()))


def second_basin(table, floor: float = 0.0) -> list[int]:
    """Indices into ``table`` ([(values, mse)], a scan: each strength once uncorrected, then
    possibly once corrected) of the best point of each local minimum of the misfit profile
    along the first parameter (per sign, from zero outwards), best first, without the global
    best's basin and without minima at strengths below ``floor`` in magnitude (the scan's
    points below the probe reach weak effects; a wiggle of a flat profile there is no basin of
    a strong one). Empty when the profile has one minimum."""
    best_at = {}
    for j, (v, m) in enumerate(table):
        key = float(v[0])
        if key not in best_at or m < table[best_at[key]][1]:
            best_at[key] = j
    minima = []
    for sign in (1.0, -1.0):
        side = sorted((v for v in best_at if v * sign > 0), key=abs)
        if not side:
            continue
        prof = [table[best_at[0.0]][1] if 0.0 in best_at else np.inf]
        prof += [table[best_at[v]][1] for v in side]
        for i, v in enumerate(side, start=1):
            right = prof[i + 1] if i + 1 < len(prof) else np.inf
            if prof[i] < prof[i - 1] and prof[i] <= right:
                minima.append(best_at[v])
    minima.sort(key=lambda j: table[j][1])
    return [j for j in minima[1:] if abs(float(table[j][0][0])) >= floor]


def linearized_start(spec, x_base, J0, sig, residual) -> np.ndarray:
    """One Gauss-Newton step from (x_base, strength 0) in the coefficients and the first effect
    parameter together: J0 (5n, k) the starting model's Jacobian, ``sig`` (n, 5) the signature
    per unit strength, ``residual`` (n, 5) measured - predicted. Clipped into the bounds."""
    probe = spec.effect_parameters[0].probe
    A = np.column_stack([J0, sig.ravel() * probe])
    delta, *_ = np.linalg.lstsq(A, residual.ravel(), rcond=None)
    k = J0.shape[1]
    rest = [1.0] * (len(spec.effect_parameters) - 1)       # further parameters at their probe
    x = np.concatenate([np.asarray(x_base, dtype=float)[:k] + delta[:k], [delta[k]], rest])
    lo, hi = spec.bounds()
    return np.clip(x, lo, hi)


def fit_effect(spec, ev, designs, measured, base_fit, J0, sig, *, max_nfev: int = 20,
               scan_points: int = 5, profile: int = 0) -> tuple[Fit, dict]:
    """Fit the starting model plus ``spec``'s effect; see the module docstring. Returns the fit
    and {"scan": [(values, mse)], "start": the start whose refinement won}."""
    measured = np.asarray(measured, dtype=float)
    x_scan, table, others = scan_effect(spec, ev, designs, measured, base_fit.x, scan_points, J0,
                                        profile)
    x_lin = linearized_start(spec, base_fit.x, J0, sig, measured - base_fit.predictions)
    starts = {"linearized": x_lin, "scan": x_scan}
    preds = ev.keypoints(spec, [x_lin, x_scan] + others[:1], designs)
    score = {k: float(np.mean((p - measured) ** 2)) for k, p in zip(starts, preds)}
    # only the start with the lower misfit is refined (half the cost; both are evaluated)
    best = min(score, key=lambda k: (score[k], k))
    fits = {best: fit(spec, ev, designs, measured, starts[best], max_nfev=max_nfev)}
    if others:
        second = float(np.mean((preds[2] - measured) ** 2))
        if second <= (1.0 + SECOND_BASIN) * min(score.values()):
            fits["scan, second basin"] = fit(spec, ev, designs, measured, others[0],
                                             max_nfev=max_nfev)
    start = min(fits, key=lambda k: (fits[k].mse_mm2, k))
    f = fits[start]
    if f.mse_mm2 > base_fit.mse_mm2:
        x0 = spec.extend(base_fit.x, (0.0,) * len(spec.effect_parameters))
        f = evaluated(spec, ev, designs, measured, x0, f.evaluations,
                      "no improvement over the starting model")
        start = "zero"
    return f, {"scan": table, "start": start}


def refine_estimate(f: Fit, ev, designs, measured, *, max_nfev: int = 25) -> tuple[Fit, dict]:
    """(better fit, record) of a named effect's model: its strength profiled at
    ``ESTIMATE_FACTORS`` times the fitted value (the coefficients refitted with the strength
    held, ``PROFILE_NFEV`` evaluations each), then least squares over every parameter from
    the lowest of the fit and the profile points. The result has a training misfit at most
    ``f``'s (``f`` itself when nothing is lower). The decision is made before this: the
    estimate is what is reported and predicted, not what was tested."""
    spec, k = f.spec, f.spec.offset
    lo, hi = spec.bounds()
    measured = np.asarray(measured, dtype=float)
    profile = []
    for a in ESTIMATE_FACTORS:
        x = np.array(f.x, dtype=float)
        x[k] = np.clip(x[k] * a, lo[k], hi[k])
        profile.append((a, fit(spec, ev, designs, measured, x, max_nfev=PROFILE_NFEV, free=k)))
    a_best, start = min(profile, key=lambda t: (t[1].mse_mm2, t[0]))
    if start.mse_mm2 >= f.mse_mm2:
        a_best, start = 1.0, f
    out = fit(spec, ev, designs, measured, start.x, max_nfev=max_nfev)
    if out.mse_mm2 >= f.mse_mm2:
        out = f
    record = {"profile": [{"factor": a, "train_mse_mm2": p.mse_mm2} for a, p in profile],
              "start_factor": a_best, "train_mse_mm2_before": f.mse_mm2,
              "train_mse_mm2": out.mse_mm2}
    return out, record


def prior_restart(f: Fit, ev, designs, measured, *, max_nfev: int = 12,
                  polish_max_nfev: int = 4, screen_spec=None) -> tuple[Fit, dict]:
    """(better fit, record) of ``f`` (an effect's model) and its refit from the starting
    material's own coefficients (``f.spec.start``, before any calibration on these rows) at
    ``f``'s effect strength: ``max_nfev`` steps at ``screen_spec``'s resolution (the effect's
    model at the screening resolution; None: ``f.spec``'s), then ``polish_max_nfev`` at
    ``f.spec``'s.

    Why: the starting model, calibrated on data that carry the missing effect, absorbs what its
    coefficients can of it, and an extended fit started from those absorbed coefficients can
    stay in their basin (measured: ``benchmarks/bench_basins.py``; on boundary_transition x3 no
    start from them ends below a training MSE of 4.31 mm^2, while 8 of 10 from the starting
    material's end at 3.40-3.52, where the true parameters' fit ends, 3.45). The result has a
    training misfit at most ``f``'s."""
    spec = f.spec
    x0 = spec.encode(spec.start, spec.decode(f.x)[1][spec.effect])
    g = walked(spec, ev, designs, measured, x0, max_nfev=max_nfev,
               polish_max_nfev=polish_max_nfev, screen_spec=screen_spec)
    kept = g.mse_mm2 < f.mse_mm2
    record = {"train_mse_mm2_before": f.mse_mm2, "train_mse_mm2_prior": g.mse_mm2,
              "kept": "prior" if kept else "calibrated"}
    return (g if kept else f), record


def walked(spec, ev, designs, measured, x0, *, max_nfev: int, polish_max_nfev: int,
           screen_spec=None) -> Fit:
    """``spec`` fitted from ``x0``: with ``screen_spec`` (the same model at the screening
    resolution) ``max_nfev`` steps there, then ``polish_max_nfev`` at ``spec``'s resolution
    (most of the walk at a quarter of the cost); without it, ``max_nfev`` steps at ``spec``'s."""
    if screen_spec is None:
        return fit(spec, ev, designs, measured, x0, max_nfev=max_nfev)
    x0 = fit(screen_spec, ev, designs, measured, x0, max_nfev=max_nfev).x
    return fit(spec, ev, designs, measured, x0, max_nfev=polish_max_nfev)


def equal_footing(base_spec, ev, designs, measured, base_fit, fits, passes, *,
                  max_nfev: int = 20, screen_spec=None, polish_max_nfev: int = 4) -> tuple[Fit, list]:
    """(best starting-model fit, [{"from", "train_mse_mm2"}]): ``base_fit`` re-polished by least
    squares from the coefficients of each fit in ``fits`` ({name: Fit}, in order) for which
    ``passes(rss0, fit)`` holds against the best starting-model RSS so far. With
    ``screen_spec`` (the starting model at the screening resolution) the re-polish is done the
    way the extended fits were made: ``max_nfev`` steps there, then ``polish_max_nfev`` at
    ``base_spec``'s resolution (most of the walk at a quarter of the cost); without it,
    ``max_nfev`` steps at ``base_spec``'s."""
    measured = np.asarray(measured, dtype=float)
    k = base_spec.size
    best, log = base_fit, []
    for name, f in fits.items():
        rss0 = float(np.sum((best.predictions - measured) ** 2))
        if not passes(rss0, f):
            continue
        fr = walked(base_spec, ev, designs, measured, np.asarray(f.x)[:k], max_nfev=max_nfev,
                    polish_max_nfev=polish_max_nfev, screen_spec=screen_spec)
        log.append({"from": name, "train_mse_mm2": fr.mse_mm2})
        if fr.mse_mm2 < best.mse_mm2:
            best = fr
    return best, log
