"""``boundary_transition``: the embroidery's properties graded over a finite width at its edge.

The paper switches rest metric and stiffness from their inside to their outside values exactly at
the boundary R_b = d / 2 eta. Here every per-segment value v (lambda, k_r, k_theta, and the hinge
weight w_b) follows a linear ramp of ``width_mm`` (rest frame) centred on R_b:
v = v_out + (v_in - v_out) phi, phi = clip(1/2 - (R_mid - R_b) / width, 0, 1), R_mid the
segment's midpoint (hinge i uses segment i's phi, as in the model). For widths below one node
spacing phi is still 0 or 1, and ``width_mm`` = 0 is the starting model (the grid is not
touched).
"""
from __future__ import annotations

import dataclasses

import numpy as np

from stitchswitch.validation.discovery.effects.registry import Effect, EffectParameter, register_effect


def ramp(grid, width_mm: float) -> np.ndarray:
    """phi of every segment: 1 well inside, 0 well outside, linear over ``width_mm``."""
    mid = (np.arange(grid.n_nodes - 1) + 0.5) * grid.dr_mm
    return np.clip(0.5 - (mid - grid.n_inside * grid.dr_mm) / width_mm, 0.0, 1.0)


def _graded(values: np.ndarray, phi: np.ndarray) -> np.ndarray:
    out = values[-1] + (values[0] - values[-1]) * phi[: values.size]
    out = np.ascontiguousarray(out, dtype=float)
    out.setflags(write=False)
    return out


def grid(grid, patch, material, values):
    (width,) = values
    phi = ramp(grid, width)
    return dataclasses.replace(grid, lam=_graded(grid.lam, phi), k_r=_graded(grid.k_r, phi),
                               k_theta=_graded(grid.k_theta, phi), w_b=_graded(grid.w_b, phi))


EFFECT = register_effect(Effect(
    name="boundary_transition",
    summary="rest metric and stiffness graded linearly over width_mm across the boundary",
    physics="Stitches near the edge pull the surrounding fabric and are themselves less dense, so "
            "the embroidered properties fade out over a finite width instead of jumping at R_b: "
            "a linear ramp of width_mm (rest frame) centred on the boundary. Zero width is the "
            "starting model.",
    parameters=(EffectParameter("width_mm", "mm", 0.0, 12.0, probe=2.0, hidden=(10.0, 11.4)),),
    grid=grid,
))
