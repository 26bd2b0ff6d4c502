"""One force scale fitted on train rows and validated on held-out rows."""
import numpy as np
import pytest

from stitchswitch.errors import InvalidInputError
from stitchswitch.fem_reference.revolution import DEFAULT_SHELL, force_scale_n_per_model
from stitchswitch.fem_reference.snap.force_scale import fit_force_scale
from stitchswitch.reduced.design_space.force_model import ForceSample
from stitchswitch.reduced.model.params import DEFAULT_MATERIAL

FORCES = {(40.0, 0.8): 0.004, (60.0, 0.8): 0.0063, (90.0, 0.6): 0.0015, (90.0, 1.0): 0.02,
          (20.0, 0.6): None}


def _samples(scale, noise=0.0, seed=0):
    rng = np.random.default_rng(seed)
    out = []
    for k, ((d, p), f) in enumerate(FORCES.items()):
        split = "val" if k % 2 else "train"
        value = 0.01 if f is None else scale * f + noise * rng.standard_normal()
        out.append(ForceSample(d, p, float(value), split, f"S{k}"))
    return out


def test_scale_is_recovered_from_synthetic_forces():
    true = force_scale_n_per_model(DEFAULT_MATERIAL, DEFAULT_SHELL) * 1.7
    fit = fit_force_scale(_samples(true), forces=FORCES, source="synthetic test")
    assert abs(fit.scale_n_per_model / true - 1) < 1e-12
    assert abs(fit.knit_stiffness_n_per_m / (1.7 * DEFAULT_SHELL.knit_stiffness_n_per_m) - 1) < 1e-12
    assert fit.r2_val == pytest.approx(1.0) and fit.mae_val_n < 1e-12
    assert fit.excluded == ((20.0, 0.6),) and fit.source == "synthetic test"


def test_noise_shows_in_the_held_out_scores():
    fit = fit_force_scale(_samples(10.0, noise=0.01), forces=FORCES)
    assert fit.mae_val_n > 0.001 and fit.r2_val < 1.0


def test_too_few_rows_are_refused():
    with pytest.raises(InvalidInputError):
        fit_force_scale(_samples(1.0)[:2], forces=FORCES)
