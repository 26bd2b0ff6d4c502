"""How much of a hidden effect a recalibration of the starting model cannot absorb.

``unabsorbed(designs, clean, start)``: the starting model (its free coefficients,
``space.BASE_FREE``) fitted to NOISE-FREE keypoints ``clean`` of a true model exactly as the
workflow's step 1 fits it (least squares at the screening resolution from ``start``, then a
polish at full resolution); what it leaves, RSS_clean (mm^2), is the part of the effect no
recalibration removes. Against noise of variance sigma^2 per keypoint that is the
noncentrality lambda = RSS_clean / sigma^2 of the F test an oracle (the true effect, fitted
exactly) would run, and "chi2" of the absorbability table in docs/discovery.md.

``oracle_power(lam, n, k1, alpha)``: that F test's probability of passing at level ``alpha``
with one extra parameter (n residuals, k1 parameters of the larger model).
"""
from __future__ import annotations

import numpy as np

__all__ = ["unabsorbed", "oracle_power"]


def unabsorbed(designs, clean, start, *, config=None) -> dict:
    """{"rss_clean_mm2", "mse_clean_mm2", "solves"} of the starting model fitted to ``clean``
    (n, 5) at ``designs`` from the material ``start``, with ``config``'s (a ``DiscoveryConfig``)
    screening resolution and step budgets."""
    from stitchswitch.validation.discovery.evaluate import Evaluator
    from stitchswitch.validation.discovery.fit import fit
    from stitchswitch.validation.discovery.space import BASE_FREE, ModelSpec
    from stitchswitch.validation.discovery.workflow import DiscoveryConfig, screen_spec

    config = config or DiscoveryConfig()
    y = np.asarray(clean, dtype=float)
    ev = Evaluator()
    base = ModelSpec(start, None, BASE_FREE)
    screen = screen_spec(start, config.screen_nodes)
    fs = fit(screen, ev, designs, y, screen.encode(screen.start), max_nfev=config.fit_max_nfev)
    fb = fit(base, ev, designs, y, fs.x, max_nfev=config.polish_max_nfev) if screen != base else fs
    rss = float(np.sum((fb.predictions - y) ** 2))
    return {"rss_clean_mm2": rss, "mse_clean_mm2": rss / y.size, "solves": ev.calls}


def oracle_power(lam: float, n: int, k1: int, alpha: float) -> float:
    """P(F > F_crit(alpha; 1, n - k1)) for the noncentral F(1, n - k1, ``lam``)."""
    from scipy.stats import f as f_dist
    from scipy.stats import ncf

    if lam <= 0:
        return 0.0
    return float(ncf.sf(f_dist.isf(alpha, 1, n - k1), 1, n - k1, lam))
