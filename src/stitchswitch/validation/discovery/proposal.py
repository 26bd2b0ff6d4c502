"""The next samples to make: designs that best tell the leading models apart.

Given the fitted leading models (the starting model and the best candidates, or a group the data
cannot separate), every design of a grid over the design space (d in [15, 100] mm, p in
[0.6, 1.0]) is solved with each of them. The *discrimination* of a design is the sum over all
pairs of models of sum_q ((y_a,q - y_b,q) / sigma_q)^2: the expected chi^2 by which one new
measurement there would favour the right model (sigma_q: the estimated noise per quantity). The
k designs are picked greedily: the most discriminating first, then each next one with its
discrimination scaled by 1 - exp(-r^2 / (2 l^2)), r its distance in the unit square of
(d, p) to the nearest chosen design (l = ``SPREAD``), so the samples spread over the space.

``separation(...)`` gives, for each pair, the design that separates it best and by how many
sigma. ``template_csv`` writes the proposal in the measured-data format (``validation.measured``)
with the keypoint columns left blank, to be filled in after fabrication.
"""
from __future__ import annotations

import itertools

import numpy as np

from stitchswitch.validation.measured import REQUIRED_COLUMNS

__all__ = ["design_grid", "SPREAD", "predictions", "propose", "template_csv"]

SPREAD = 0.2
D_RANGE_MM, P_RANGE = (15.0, 100.0), (0.6, 1.0)


def design_grid(nd: int = 12, np_: int = 9) -> list[tuple[float, float]]:
    """The candidate designs: ``nd`` diameters x ``np_`` fills, rounded like a design file."""
    d = np.round(np.linspace(*D_RANGE_MM, nd), 1)
    p = np.round(np.linspace(*P_RANGE, np_), 2)
    return [(float(a), float(b)) for a in d for b in p]


def predictions(ev, models, designs) -> dict:
    """{label: (n, 5) keypoints} of every (label, spec, x) in ``models`` at ``designs``."""
    return {label: ev.one(spec, x, designs) for label, spec, x in models}


def _unit(designs) -> np.ndarray:
    a = np.asarray(designs, dtype=float)
    return np.column_stack([(a[:, 0] - D_RANGE_MM[0]) / (D_RANGE_MM[1] - D_RANGE_MM[0]),
                            (a[:, 1] - P_RANGE[0]) / (P_RANGE[1] - P_RANGE[0])])


def propose(preds: dict, designs, sigma_mm, k: int = 5) -> dict:
    """{"designs": [{"d_mm", "fill", "discrimination", "pairs": {a|b: chi2}}] (k, best
    first), "separation": [{"models", "d_mm", "fill", "sigmas"}]} from ``predictions``."""
    labels = list(preds)
    sigma = np.maximum(np.asarray(sigma_mm, dtype=float), 1e-6)
    pairs = list(itertools.combinations(labels, 2))
    if not pairs:
        return {"designs": [], "separation": []}
    chi = {f"{a}|{b}": np.sum(((preds[a] - preds[b]) / sigma) ** 2, axis=1) for a, b in pairs}
    score = np.sum(list(chi.values()), axis=0)
    u = _unit(designs)
    chosen, weight = [], np.ones(len(designs))
    for _ in range(min(k, len(designs))):
        j = int(np.argmax(score * weight))
        chosen.append(j)
        r2 = np.sum((u - u[j]) ** 2, axis=1)
        weight = np.minimum(weight, 1.0 - np.exp(-r2 / (2 * SPREAD ** 2)))
    out = [{"d_mm": designs[j][0], "fill": designs[j][1], "discrimination": float(score[j]),
            "pairs": {key: float(v[j]) for key, v in chi.items()}} for j in chosen]
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
