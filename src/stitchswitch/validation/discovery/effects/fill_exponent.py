"""``fill_exponent``: the embroidery's weight p^2 replaced by p^alpha.

Inside the patch the paper weights the rest-metric excess and every stiffness by p^2
(``reduced.model.discretization``). With alpha = 2 + delta the inside values become
v_fab + (v_inside - v_fab) p^delta (v = lambda, k_r, k_theta, w_b; v_fab the outside value), i.e.
lambda = 1 + (eta - 1) p^alpha and k = k_emb p^alpha + k_fab (1 - p^alpha). At p = 1 nothing
changes. ``delta`` = 0 is the starting model (the grid is not touched).
"""
from __future__ import annotations

import dataclasses

import numpy as np

from stitchswitch.validation.discovery.effects.registry import Effect, EffectParameter, register_effect


def _reweight(values: np.ndarray, factor: np.ndarray) -> np.ndarray:
    out = values[-1] + (values - values[-1]) * factor[: values.size]
    out = np.ascontiguousarray(out, dtype=float)
    out.setflags(write=False)
    return out


def grid(grid, patch, material, values):
    (delta,) = values
    factor = np.where(grid.inside, patch.fill ** delta, 1.0)
    return dataclasses.replace(grid, lam=_reweight(grid.lam, factor),
                               k_r=_reweight(grid.k_r, factor),
                               k_theta=_reweight(grid.k_theta, factor),
                               w_b=_reweight(grid.w_b, factor))


EFFECT = register_effect(Effect(
    name="fill_exponent",
    summary="fill weighting p^2 replaced by p^alpha, alpha = 2 + delta",
    physics="The embroidery's share of the rest metric and of every stiffness grows as p^alpha "
            "instead of the paper's p^2 (for instance because overlapping stitches at high fill "
            "add less than their area). Nothing changes at p = 1; delta = 0 is the starting "
            "model.",
    parameters=(EffectParameter("delta", "1", -1.5, 3.0, probe=0.25, hidden=(1.5, 2.0),
                                signed=True),),
    grid=grid,
))
