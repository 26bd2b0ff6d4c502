"""Following the branch: where a negative natural curvature (``tension_asymmetry``) makes the
released state bistable, the cold solve's equilibrium jumps with the parameters; the
evaluator's branch states and ``fit.follow_branches`` let a fit follow the branch the data are
on. Noise-free SYNTHETIC data at the screening resolution (150 nodes)."""
import numpy as np
import pytest

from stitchswitch.reduced.calibration.evolution import search_material
from stitchswitch.validation.discovery.evaluate import Evaluator
from stitchswitch.validation.discovery.fit import fit, fit_effect, follow_branches, jacobian
from stitchswitch.validation.discovery.signature import signature
from stitchswitch.validation.discovery.space import ModelSpec
from stitchswitch.validation.discovery.synthetic import (
    START_MATERIAL,
    TRAIN_D_MM,
    TRAIN_FILL,
    TRUE_MATERIAL,
    true_keypoints,
)

START = search_material(START_MATERIAL, 150)
TRUE = search_material(TRUE_MATERIAL, 150)
KAPPA = -0.015
PAPER = [(float(d), float(p)) for p in TRAIN_FILL for d in TRAIN_D_MM]


@pytest.fixture(scope="module")
def curled_data():
    y, bad = true_keypoints(PAPER, "tension_asymmetry", (KAPPA,), TRUE)
    assert bad == 0
    assert np.sum(y[:, 0] < 1.5) >= 4          # several designs settle curled, not popped
    return y


def _fit(designs, y, targets):
    ev = Evaluator(targets=dict(zip(designs, y)) if targets else None)
    base = ModelSpec(START)
    spec = base.with_effect("tension_asymmetry")
    fb = fit(base, ev, designs, y, base.encode(START), max_nfev=25)
    J0 = jacobian(base, ev, designs, fb.x, *base.bounds())
    f, _ = fit_effect(spec, ev, designs, y, fb, J0, signature(spec, ev, designs, fb.x),
                      max_nfev=12)
    return fb, f, ev


def test_the_branch_following_fit_reaches_a_negative_curvature_the_cold_fit_cannot(curled_data):
    y = curled_data
    fb_cold, f_cold, ev_cold = _fit(PAPER, y, targets=False)
    fb, f, ev = _fit(PAPER, y, targets=True)
    assert fb.mse_mm2 == pytest.approx(fb_cold.mse_mm2)     # the starting model is unchanged
    # cold solves: the fit stops short of the truth where the curled designs' equilibria jump
    # with the parameters. How far short depends on the round-off of the jumps (measured with
    # OpenBLAS's SkylakeX kernel: kappa -0.0049, MSE 0.21 mm^2 from 1.18; Haswell: -0.0089,
    # 0.014 mm^2)
    cold_gap = abs(f_cold.parameters["kappa_per_mm"] - KAPPA)
    assert cold_gap > 0.3 * abs(KAPPA)
    assert not ev_cold.branches
    # following the branch: near the true curvature (SkylakeX -0.0115, MSE 0.0044 mm^2;
    # Haswell -0.01496, 5e-5 mm^2), at most half the cold fit's distance from it and a tenth
    # of its misfit
    assert f.parameters["kappa_per_mm"] < 0.66 * KAPPA
    assert abs(f.parameters["kappa_per_mm"] - KAPPA) < 0.5 * cold_gap
    assert f.mse_mm2 < 0.05 * fb.mse_mm2 and f.mse_mm2 < 0.1 * f_cold.mse_mm2
    assert ev.branches


def test_a_design_takes_the_branch_nearest_its_row_and_only_with_a_target():
    design = (40.0, 0.8)      # cold at -0.01 it curls (h 0.46 mm), followed it stays popped (5.84)
    spec = ModelSpec(TRUE, "tension_asymmetry")
    xs = [spec.extend(spec.encode(TRUE), (v,)) for v in np.linspace(0.0, -0.01, 6)]
    x = xs[-1]
    probe = Evaluator()
    cold = probe.one(spec, x, [design])[0]
    # followed outward from zero, the patch stays popped; the cold solve at -0.01 curls
    followed = probe.continued(spec, xs, [design])[-1]
    popped, state = followed[0][0], followed[1][0]
    assert popped[0] - cold[0] > 4.0
    for target, expect in ((popped, popped), (cold, cold)):
        ev = Evaluator(targets={design: target})
        assert np.array_equal(ev.one(spec, x, [design])[0], cold)   # no branch state: cold
        assert ev.add_branch(design, state, "tension_asymmetry")
        assert np.allclose(ev.one(spec, x, [design])[0], expect, atol=1e-6)
        # another effect's models do not use it; the starting model does (the reference)
        other = ModelSpec(TRUE, "hoop_bending")
        assert np.array_equal(ev.one(other, other.encode(TRUE), [design])[0],
                              Evaluator().one(other, other.encode(TRUE), [design])[0])
    # without a target (a validation row) a branch state is refused and the solve stays cold
    ev = Evaluator()
    assert not ev.add_branch(design, state, "tension_asymmetry")
    assert np.array_equal(ev.one(spec, x, [design])[0], cold)
    # follow_branches finds that state itself along the scan when the row is the popped one
    ev = Evaluator(targets={design: popped})
    assert follow_branches(spec, ev, [design], xs) == 1
    assert np.allclose(ev.one(spec, x, [design])[0], popped, atol=1e-3)
    assert follow_branches(spec, Evaluator(), [design], xs) == 0     # off without targets
