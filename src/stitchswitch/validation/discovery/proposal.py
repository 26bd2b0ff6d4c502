"""The next samples to make: designs that best tell the leading models apart.

Given the fitted leading models (the starting model and the best candidates, or a group the data
cannot separate), every design of a grid over the design space (d in [15, 100] mm, p in
[0.6, 1.0]) is solved with each of them. The raw *difference* of a design for a pair of models
is sum_q ((y_a,q - y_b,q) / sigma_q)^2 (sigma_q: the estimated noise per quantity).

A raw difference is not what a new measurement decides: once the rows are added, both models
are refitted, and a difference that their coefficients can absorb (moving a little away from the
current data, typically where the data are thin, beyond the training designs) separates
nothing. So the score of a set S of new designs is, for each pair and each way round, the
misfit the refitted rival cannot avoid (a linearized refit, Atkinson and Fedorov's
T-optimality):

    T_b(S) = delta_S^T (Sigma_S + J_b,S C_b J_b,S^T)^-1 delta_S

with delta_S = y_a - y_b at S (5 |S|), Sigma_S the noise covariance of the new rows, J_b,S the
rival's sensitivities there (finite differences, ``fit.jacobian``) and C_b = (J_b^T Sigma^-1
J_b + PRIOR I)^-1 the covariance of its parameters on the current training rows: the minimum
over a parameter change Delta of the new rows' chi^2 plus Delta's cost on the old ones. The
*discrimination* of S is the mean of T_a and T_b summed over the pairs (an expected chi^2).

The k designs are picked greedily: each next one the largest gain of the discrimination of the
set, scaled by 1 - exp(-r^2 / (2 l^2)), r its distance in the unit square of (d, p) to the
nearest chosen design (l = ``SPREAD``), so the samples spread over the space.

**Branches.** Where a design is bistable, a model's cold solve may sit on one equilibrium while
it has another near the rival's: once the design is measured, the workflow evaluates it on the
equilibrium nearest the row (``evaluate``, branch states), and the difference vanishes. So each
model is also solved warm-started from the rival's equilibrium at every candidate design
(``reachable``), and a pair's difference at a design is the smallest over the equilibria each
model reaches there: the difference that survives the branch choice.

``separation(...)`` gives, for each pair, the design that separates it best and by how many
sigma. ``template_csv`` writes the proposal in the measured-data format (``validation.measured``)
with the keypoint columns left blank, to be filled in after fabrication.
"""
from __future__ import annotations

import itertools
from dataclasses import dataclass

import numpy as np

from stitchswitch.validation.measured import REQUIRED_COLUMNS

__all__ = ["design_grid", "SPREAD", "PRIOR", "ModelView", "model_view", "predictions",
           "reachable", "surviving_difference", "propose", "template_csv"]

SPREAD = 0.2
#: Prior precision (per search unit squared) that keeps the parameter covariance finite along
#: directions the training rows do not determine.
PRIOR = 1e-2
D_RANGE_MM, P_RANGE = (15.0, 100.0), (0.6, 1.0)


def design_grid(nd: int = 12, np_: int = 9) -> list[tuple[float, float]]:
    """The candidate designs: ``nd`` diameters x ``np_`` fills, rounded like a design file."""
    d = np.round(np.linspace(*D_RANGE_MM, nd), 1)
    p = np.round(np.linspace(*P_RANGE, np_), 2)
    return [(float(a), float(b)) for a in d for b in p]


@dataclass(frozen=True)
class ModelView:
    """One fitted model on the candidate designs: ``pred`` (n, 5) keypoints, ``jac`` (n, 5, k)
    their sensitivities to the search vector, ``cov`` (k, k) the parameter covariance on the
    training rows (None: the raw differences only)."""

    pred: np.ndarray
    jac: np.ndarray | None = None
    cov: np.ndarray | None = None


def model_view(ev, spec, x, designs, train_designs, sigma_mm, jac_spec=None) -> ModelView:
    """The ``ModelView`` of (``spec``, ``x``) at ``designs``; the sensitivities are finite
    differences with ``jac_spec`` (the same model at a coarser resolution, cheaper; None:
    ``spec``) at the candidate designs and at ``train_designs``."""
    from stitchswitch.validation.discovery.fit import jacobian

    js = jac_spec or spec
    lo, hi = js.bounds()
    sigma = np.maximum(np.asarray(sigma_mm, dtype=float), 1e-6)
    pred = ev.one(spec, x, designs)
    J = jacobian(js, ev, designs, x, lo, hi).reshape(len(designs), 5, -1)
    Jt = jacobian(js, ev, train_designs, x, lo, hi).reshape(len(train_designs), 5, -1)
    Jw = (Jt / sigma[None, :, None]).reshape(-1, Jt.shape[2])
    cov = np.linalg.inv(Jw.T @ Jw + PRIOR * np.eye(Jw.shape[1]))
    return ModelView(pred, J, cov)


def predictions(ev, models, designs) -> dict:
    """{label: (n, 5) keypoints} of every (label, spec, x) in ``models`` at ``designs``."""
    return {label: ev.one(spec, x, designs) for label, spec, x in models}


def reachable(ev, models, designs) -> dict:
    """{(a, b): (n, 5)}: model ``a`` at ``designs`` warm-started from model ``b``'s equilibria
    there, for every ordered pair of ``models`` ((label, spec, x)): the equilibrium of ``a``
    nearest ``b``'s, where it has one."""
    states = {label: [ev.solution(spec, x, d) for d in designs] for label, spec, x in models}
    return {(a, b): ev.from_states(spec, x, designs, states[b])
            for a, spec, x in models for b, *_ in models if a != b}


def surviving_difference(pred_a, pred_b, sigma, alt_a=(), alt_b=()) -> np.ndarray:
    """(n, 5) difference a - b at each design taken between the equilibria (``pred`` and the
    ``alt`` ones) of each model that are nearest each other there (smallest sum of squared
    sigma-scaled differences)."""
    A = np.stack([pred_a, *alt_a])
    B = np.stack([pred_b, *alt_b])
    d = A[:, None] - B[None, :]
    flat = d.reshape(-1, *d.shape[2:])
    k = np.argmin(np.sum((flat / sigma) ** 2, axis=-1), axis=0)
    return flat[k, np.arange(flat.shape[1])]


def _unit(designs) -> np.ndarray:
    a = np.asarray(designs, dtype=float)
    return np.column_stack([(a[:, 0] - D_RANGE_MM[0]) / (D_RANGE_MM[1] - D_RANGE_MM[0]),
                            (a[:, 1] - P_RANGE[0]) / (P_RANGE[1] - P_RANGE[0])])


def _unavoidable(delta, rival: ModelView, rows, sigma) -> float:
    """delta^T (Sigma + J C J^T)^-1 delta over the designs ``rows`` (the refitted rival's
    misfit there); the raw chi^2 when the rival has no sensitivities."""
    d = delta[rows].ravel()
    S = np.diag(np.tile(sigma ** 2, len(rows)))
    if rival.jac is not None:
        J = rival.jac[rows].reshape(len(d), -1)
        S = S + J @ rival.cov @ J.T
    return float(d @ np.linalg.solve(S, d))


def propose(views: dict, designs, sigma_mm, k: int = 5, reach: dict | None = None) -> dict:
    """{"designs": [{"d_mm", "fill", "discrimination", "gain", "pairs": {a|b: chi2}}] (k, in
    the order chosen; ``discrimination``: of the set so far, ``gain``: what this design added,
    ``pairs``: the raw difference of each pair there), "separation": [{"models", "d_mm",
    "fill", "sigmas"}]} from {label: ``ModelView`` or (n, 5) keypoints}; ``reach``: the
    equilibria each model reaches from the other's (``reachable``), for the difference that
    survives the branch choice (``surviving_difference``)."""
    views = {a: (v if isinstance(v, ModelView) else ModelView(np.asarray(v, dtype=float)))
             for a, v in views.items()}
    labels = list(views)
    sigma = np.maximum(np.asarray(sigma_mm, dtype=float), 1e-6)
    pairs = list(itertools.combinations(labels, 2))
    if not pairs:
        return {"designs": [], "separation": []}
    reach = reach or {}
    delta = {(a, b): surviving_difference(
        views[a].pred, views[b].pred, sigma,
        [reach[a, b]] if (a, b) in reach else (), [reach[b, a]] if (b, a) in reach else ())
        for a, b in pairs}
    chi = {f"{a}|{b}": np.sum((delta[a, b] / sigma) ** 2, axis=1) for a, b in pairs}

    def score(rows):
        return sum(0.5 * (_unavoidable(delta[a, b], views[b], rows, sigma)
                          + _unavoidable(delta[a, b], views[a], rows, sigma)) for a, b in pairs)

    u = _unit(designs)
    chosen, weight, current, out = [], np.ones(len(designs)), 0.0, []
    for _ in range(min(k, len(designs))):
        gains = np.array([score(chosen + [j]) - current if j not in chosen else -np.inf
                          for j in range(len(designs))])
        j = int(np.argmax(np.where(np.isfinite(gains), np.maximum(gains, 0.0) * weight, -1.0)))
        chosen.append(j)
        current += float(gains[j])
        r2 = np.sum((u - u[j]) ** 2, axis=1)
        weight = np.minimum(weight, 1.0 - np.exp(-r2 / (2 * SPREAD ** 2)))
        out.append({"d_mm": designs[j][0], "fill": designs[j][1], "discrimination": current,
                    "gain": float(gains[j]),
                    "pairs": {key: float(v[j]) for key, v in chi.items()}})
    sep = []
    for (a, b), v in zip(pairs, chi.values()):
        j = int(np.argmax(v))
        sep.append({"models": [a, b], "d_mm": designs[j][0], "fill": designs[j][1],
                    "sigmas": float(np.sqrt(v[j]))})
    return {"designs": out, "separation": sep}


def template_csv(proposal: dict, note: str = "") -> str:
    """The proposed designs as a measured-data CSV with blank keypoints (split train)."""
    lines = ["# source: TEMPLATE of proposed samples (stitchswitch discover); fill in the "
             "measured keypoints (mm) before use" + (f"; {note}" if note else ""),
             "sample_id," + ",".join(REQUIRED_COLUMNS)]
    for k, row in enumerate(proposal["designs"], start=1):
        lines.append(f"next{k:02d},{row['d_mm']:g},{row['fill']:g},,,,,,train")
    return "\n".join(lines) + "\n"
