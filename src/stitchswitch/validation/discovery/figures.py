"""Figures of the discovery report (PNG bytes, matplotlib Agg, deterministic for equal input).

* ``residual_maps``: the residual (measured - predicted) of each quantity over the design space
  (d, fill), train rows as circles, validation rows as triangles, a diverging colour scale
  symmetric about zero (shared by the before and after maps), the residual test in the title.
* ``ranking``: cross-validated error of every candidate against the starting model's.
* ``signatures``: the starting model's training residuals next to the pattern each of the best
  candidates explains (its unabsorbable signature times the linearized strength).
* ``before_after``: validation MAE per quantity before and after adding the named effect.
"""
from __future__ import annotations

import numpy as np

from stitchswitch.files.figures import plot_bytes
from stitchswitch.validation.measured import QUANTITIES

__all__ = ["residual_maps", "ranking", "signatures", "before_after", "all_figures", "FIGURES"]

FIGURES = ("residuals_before.png", "residuals_after.png", "ranking.png", "signatures.png",
           "before_after.png")
_MARKERS = {"train": "o", "val": "^"}


def _plt():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def _png(fig) -> bytes:
    return plot_bytes(fig)


def _map(ax, d, p, values, limit, marker="o", label=None):
    return ax.scatter(d, p, c=values, cmap="RdBu_r", vmin=-limit, vmax=limit, s=46,
                      marker=marker, edgecolors="black", linewidths=0.4, label=label)


def residual_maps(disc, which: str, limits) -> bytes:
    """Residual maps of ``which`` ("before" or "after"); ``limits`` (5,) colour limits (mm)."""
    plt = _plt()
    pred = disc.before if which == "before" else disc.after
    res = disc.measured - pred
    tests = disc.summary[f"residuals_{which}"]
    fig, axes = plt.subplots(1, 5, figsize=(19.0, 4.0), dpi=90)
    for k, q in enumerate(QUANTITIES):
        ax = axes[k]
        for s, mk in _MARKERS.items():
            sel = disc.split == s
            sc = _map(ax, disc.diameter_mm[sel], disc.fill[sel], res[sel, k], limits[k], mk,
                      f"{s} ({int(sel.sum())})")
        t = tests[q]
        verdict = "systematic" if t["systematic"] else "noise-like"
        ax.set_title(f"{q}: {verdict}\nCV R2 {t['cv_r2']:.2f}, p = {t['p_value']:.3g}",
                     fontsize=9.5)
        ax.set_xlabel("d (mm)")
        if k == 0:
            ax.set_ylabel("fill p")
            ax.legend(fontsize=7, loc="lower right")
        fig.colorbar(sc, ax=ax, shrink=0.85, label="measured - predicted (mm)")
    title = {"before": "Residuals of the calibrated starting model",
             "after": "Residuals after adding " + (disc.summary["missing_effect"] or
                                                   "nothing (no missing effect named)")}[which]
    fig.suptitle(title, fontsize=12)
    fig.tight_layout()
    return _png(fig)


def ranking(disc) -> bytes:
    plt = _plt()
    rows = disc.ranking
    base = disc.summary["starting_model"]["cv_score_mm2"]
    fig, ax = plt.subplots(figsize=(8.0, 0.55 * len(rows) + 1.8), dpi=100)
    names = [r.effect for r in rows][::-1]
    scores = [r.cv_mse_mm2 for r in rows][::-1]
    colors = ["tab:green" if r.significant else "0.6" for r in rows][::-1]
    ax.barh(names, scores, color=colors, edgecolor="black", linewidth=0.5)
    ax.axvline(base, color="tab:red", ls="--", lw=1.2, label=f"starting model {base:.2f}")
    for y, r in enumerate(rows[::-1]):
        ax.text(r.cv_mse_mm2, y, f"  p = {r.p_value:.2g}", va="center", fontsize=8)
    ax.set_xlabel("cross-validated MSE on the training rows (mm$^2$), lower is better")
    ax.set_title("Candidates ranked (green: significant and better than the starting model)",
                 fontsize=11)
    ax.legend(fontsize=8, loc="lower right")
    ax.set_xlim(0, max(max(scores), base) * 1.25)
    fig.tight_layout()
    return _png(fig)


def signatures(disc, top: int = 3) -> bytes:
    """Row 1: training residuals of the starting model; then the pattern explained by each of
    the ``top`` best-ranked candidates."""
    plt = _plt()
    tr = disc.split == "train"
    res = (disc.measured - disc.before)[tr]
    rows = [("starting-model residual", res)]
    for r in disc.ranking[:top]:
        c = r.signature["correlation"]
        rows.append((f"{r.effect} (corr {c:+.2f})", disc.signatures[r.effect]["pattern"]))
    limits = np.maximum(np.max(np.abs(res), axis=0), 1e-6)
    fig, axes = plt.subplots(len(rows), 5, figsize=(17.0, 3.0 * len(rows)), dpi=80, squeeze=False)
    for i, (label, values) in enumerate(rows):
        for k, q in enumerate(QUANTITIES):
            ax = axes[i, k]
            sc = _map(ax, disc.diameter_mm[tr], disc.fill[tr], values[:, k], limits[k])
            ax.set_title(f"{label}: {q}" if k == 0 else q, fontsize=9)
            if i == len(rows) - 1:
                ax.set_xlabel("d (mm)")
            if k == 0:
                ax.set_ylabel("fill p")
            fig.colorbar(sc, ax=ax, shrink=0.8)
    fig.suptitle("Residual pattern (top row) and the part of it each candidate can explain "
                 "(its signature beyond what recalibration absorbs), mm", fontsize=11)
    fig.tight_layout()
    return _png(fig)


def before_after(disc) -> bytes:
    plt = _plt()
    b = [disc.summary["before"][q]["mae_mm"] for q in QUANTITIES]
    a = [disc.summary["after"][q]["mae_mm"] for q in QUANTITIES]
    x = np.arange(len(QUANTITIES))
    fig, ax = plt.subplots(figsize=(7.0, 3.8), dpi=100)
    ax.bar(x - 0.2, b, 0.4, label="starting model (calibrated)", color="0.65", edgecolor="black",
           linewidth=0.5)
    name = disc.summary["missing_effect"]
    ax.bar(x + 0.2, a, 0.4, label=f"with {name}" if name else "unchanged (no effect named)",
           color="tab:green" if name else "0.85", edgecolor="black", linewidth=0.5)
    ax.set_xticks(x, QUANTITIES)
    ax.set_ylabel("validation MAE (mm)")
    ax.set_title("The gap on the validation rows", fontsize=11)
    ax.legend(fontsize=8)
    fig.tight_layout()
    return _png(fig)


def all_figures(disc) -> dict:
    """{file name: PNG bytes} of every figure."""
    lim = np.max(np.abs(np.concatenate([disc.measured - disc.before, disc.measured - disc.after])),
                 axis=0)
    lim = np.maximum(lim, 1e-6)
    return {"residuals_before.png": residual_maps(disc, "before", lim),
            "residuals_after.png": residual_maps(disc, "after", lim),
            "ranking.png": ranking(disc), "signatures.png": signatures(disc),
            "before_after.png": before_after(disc)}
