"""A synthetic force-displacement curve (SYNTHETIC: made-up numbers in the shape of a snap-through
path, no shell solved) for the tests of the switch-force plot and CSV and their golden files."""
from __future__ import annotations

from types import SimpleNamespace

import numpy as np

from stitchswitch.fem_reference.snap.path import SwitchingPath
from stitchswitch.reduced.model.params import Patch


def _state(apex_mm: float, energy: float) -> SimpleNamespace:
    """What ``SwitchingPath.as_dict`` reads of a shell state."""
    kp = SimpleNamespace(h_mm=abs(apex_mm), r_a_mm=20.0, z_a_mm=apex_mm / 2, r_b_mm=30.0,
                         z_b_mm=0.0)
    return SimpleNamespace(keypoints=kp, energy=energy, certified=True, apex_mm=apex_mm)


def synthetic_curve() -> SwitchingPath:
    w = np.linspace(8.0, -4.0, 13)
    force = np.maximum(0.0, np.sin(np.linspace(0.0, 1.2 * np.pi, 13))) * 3.0e-3
    return SwitchingPath(
        patch=Patch(60.0, 0.8), plate_radius_mm=15.0, w_mm=w, force=force,
        elastic_energy=np.linspace(1.0, 2.0, 13), apex_mm=w, converged=np.ones(13, dtype=bool),
        switching_force=float(force.max()), w_switch_mm=float(w[np.argmax(force)]),
        barrier=0.5, popup=_state(8.0, 1.0), final=_state(-6.0, 1.2), inverted=True, newton_per_n=2.5, elapsed_s=0.0)
