"""The stepped cross-validation (``cv.cross_validate_stepped``): one damped Gauss-Newton step per
fold from the full fit, held-out designs warm-started from the full fit's equilibria.

On a coarse discretization (80 nodes, dR_max = 1 mm) and six monostable designs, so that every
warm-started solve has one equilibrium to find.
"""
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

from stitchswitch.errors import InvalidInputError
from stitchswitch.validation.discovery.cv import (
    cross_validate_stepped,
    damped_step,
    fold_labels,
)
from stitchswitch.validation.discovery.evaluate import Evaluator
from stitchswitch.validation.discovery.space import ModelSpec
from stitchswitch.validation.discovery.synthetic import START_MATERIAL
from stitchswitch.validation.discovery.workflow import DiscoveryConfig, fold_refits

START = START_MATERIAL.replace(n_nodes=80, dr_max_mm=1.0)
DESIGNS = [(30.0, 0.8), (50.0, 1.0), (70.0, 0.7), (40.0, 0.9), (60.0, 0.6), (80.0, 1.0)]
TRUTH = START.replace(w_b_emb=1.4 * START.w_b_emb, k_r_emb=1.6 * START.k_r_emb)


@pytest.fixture(scope="module")
def problem():
    """(spec, evaluator, noise-free rows of TRUTH, the true x, fold labels)."""
    spec = ModelSpec(START, None, ("w_b_emb", "k_r_emb"))
    ev = Evaluator()
    x_true = spec.encode(TRUTH)
    return spec, ev, ev.one(spec, x_true, DESIGNS), x_true, fold_labels(DESIGNS, 3, 0)


@settings(max_examples=60, deadline=None)
@given(arrays(np.float64, (12, 3), elements=st.floats(-10, 10)),
       arrays(np.float64, 12, elements=st.floats(-10, 10)),
       st.floats(1e-3, 10.0))
def test_the_damped_step_solves_the_levenberg_marquardt_normal_equations(J, r, damping):
    """(J^T J + damping diag(J^T J)) dx = J^T r, for any J whose columns all act."""
    J = J + np.eye(12, 3)               # no zero column
    dx = damped_step(J, r, damping)
    JtJ = J.T @ J
    lhs = (JtJ + damping * np.diag(np.diag(JtJ))) @ dx
    assert np.allclose(lhs, J.T @ r, atol=1e-8 * (1 + np.abs(J.T @ r).max()))


def test_the_damped_step_leaves_a_parameter_without_influence_where_it_is():
    rng = np.random.default_rng(0)
    J = rng.normal(size=(10, 3))
    J[:, 1] = 0.0
    dx = damped_step(J, rng.normal(size=10), 0.1)
    assert dx[1] == 0.0 and np.all(np.isfinite(dx))
    # and without damping it is the Gauss-Newton (least-squares) step of the other columns
    r = rng.normal(size=10)
    gn = np.linalg.lstsq(J[:, [0, 2]], r, rcond=None)[0]
    assert np.allclose(damped_step(J, r, 1e-12)[[0, 2]], gn, rtol=1e-6)


def test_at_the_exact_optimum_of_noise_free_rows_no_fold_moves(problem):
    spec, ev, measured, x_true, labels = problem
    cv = cross_validate_stepped(spec, ev, DESIGNS, measured, x_true, labels)
    assert cv.folds == 3 and cv.stuck_folds == 3
    assert cv.score_mm2 < 1e-10


def test_one_undamped_step_from_near_the_optimum_lands_near_it(problem):
    """Gauss-Newton converges quadratically on zero-residual data: one step from 0.02 (log10)
    away ends within a tenth of that of the truth, in every fold (measured: 1-5 %), and the
    held-out error falls by far more than half. A wrong sign or a Jacobian restricted to the
    wrong rows fails this."""
    spec, ev, measured, x_true, labels = problem
    x0 = x_true + np.array([0.02, -0.016])
    cv = cross_validate_stepped(spec, ev, DESIGNS, measured, x0, labels, damping=1e-9)
    for x in cv.fold_parameters:
        assert np.abs(x - x_true).max() < 0.1 * 0.02
    unstepped = np.mean((ev.one(spec, x0, DESIGNS) - measured) ** 2)
    assert cv.score_mm2 < 0.02 * unstepped


def test_damping_shortens_the_step(problem):
    spec, ev, measured, x_true, labels = problem
    x0 = x_true + np.array([0.05, -0.04])
    light = cross_validate_stepped(spec, ev, DESIGNS, measured, x0, labels, damping=1e-9)
    heavy = cross_validate_stepped(spec, ev, DESIGNS, measured, x0, labels, damping=10.0)
    for a, b in zip(light.fold_parameters, heavy.fold_parameters):
        assert 0 < np.linalg.norm(b - x0) < 0.5 * np.linalg.norm(a - x0)


def test_a_step_stays_within_the_radius(problem):
    spec, ev, measured, x_true, labels = problem
    x0 = x_true + np.array([0.3, -0.3])
    free = cross_validate_stepped(spec, ev, DESIGNS, measured, x0, labels)
    assert max(np.abs(x - x0).max() for x in free.fold_parameters) > 0.06
    boxed = cross_validate_stepped(spec, ev, DESIGNS, measured, x0, labels, radius=0.05)
    assert all(np.abs(x - x0).max() <= 0.05 + 1e-12 for x in boxed.fold_parameters)


def test_held_out_designs_are_predicted_at_the_fold_parameters(problem):
    """Warm-started from the full fit's equilibria, a monostable held-out design reaches the
    same equilibrium as a cold solve at the fold's parameters."""
    spec, ev, measured, x_true, labels = problem
    x0 = x_true + np.array([0.05, -0.04])
    cv = cross_validate_stepped(spec, ev, DESIGNS, measured, x0, labels)
    for k, x in enumerate(cv.fold_parameters):
        held = [d for d, label in zip(DESIGNS, labels) if label == k]
        assert np.allclose(cv.predictions[labels == k], ev.one(spec, x, held), atol=1e-6)


def test_the_config_chooses_the_method_of_the_full_resolution_cross_validation(problem):
    spec, ev, measured, x_true, labels = problem
    x0 = x_true + np.array([0.05, -0.04])
    stepped = fold_refits(spec, ev, DESIGNS, measured, x0, labels,
                          DiscoveryConfig(cv_method="stepped", cv_damping=0.3))
    direct = cross_validate_stepped(spec, ev, DESIGNS, measured, x0, labels, damping=0.3,
                                    radius=DiscoveryConfig().cv_radius)
    assert np.array_equal(stepped.predictions, direct.predictions)
    refit = fold_refits(spec, ev, DESIGNS, measured, x0, labels,
                        DiscoveryConfig(cv_method="refit"))
    assert not np.array_equal(refit.predictions, stepped.predictions)
    with pytest.raises(InvalidInputError, match="cv_method: 'newton'"):
        DiscoveryConfig(cv_method="newton")
    with pytest.raises(InvalidInputError, match="cv_damping"):
        DiscoveryConfig(cv_damping=0.0)


def test_a_fold_steps_towards_the_least_squares_fit_of_its_training_rows(problem):
    """On noisy rows the step from the noise-free optimum is the linear estimate of the fold's
    own refit: near the least-squares fit of the fold's training rows, not of its held-out
    ones (measured: 1-35 % of the refit's move off, against 77-112 % for the held-out fit)."""
    from stitchswitch.validation.discovery.fit import fit

    spec, ev, clean, x_true, labels = problem
    measured = clean + np.random.default_rng(3).normal(0.0, 0.1, clean.shape)
    cv = cross_validate_stepped(spec, ev, DESIGNS, measured, x_true, labels, damping=1e-9)
    for k, x in enumerate(cv.fold_parameters):
        test = labels == k
        rows = [d for d, t in zip(DESIGNS, test) if not t]
        held = [d for d, t in zip(DESIGNS, test) if t]
        own = fit(spec, ev, rows, measured[~test], x_true, max_nfev=30).x
        other = fit(spec, ev, held, measured[test], x_true, max_nfev=30).x
        assert np.linalg.norm(x - own) < 0.5 * np.linalg.norm(own - x_true)
        assert np.linalg.norm(x - own) < 0.5 * np.linalg.norm(x - other)
