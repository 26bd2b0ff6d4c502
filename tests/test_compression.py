"""The compressive response as physics (``compression.tension_field``): its derivatives, its
limit cases, and the convergence of the keypoints as its numerical floor goes to zero."""
import numpy as np
import pytest

from stitchswitch import DEFAULT_MATERIAL, Patch, solve
from stitchswitch.errors import InvalidInputError
from stitchswitch.reduced.calibration.designs import CALIBRATION_DESIGNS
from stitchswitch.reduced.model import assembly
from stitchswitch.reduced.model.discretization import make_grid
from stitchswitch.reduced.model.terms import ALL_TERMS, compression

from helpers import fd_gradient, fd_jacobian, pack, random_state

KEYS = ("h_mm", "r_a_mm", "z_a_mm", "r_b_mm", "z_b_mm")


def with_field(fill, c_fab=0.0, jam=0.5, floor=1e-6, c_emb=0.01):
    field = compression.tension_field(fill, c_emb, c_fab, jam, floor)
    return tuple(field if t is compression.TERM else t for t in ALL_TERMS)


def keypoints(d, p, **kw):
    sol = solve(Patch(d, p), DEFAULT_MATERIAL, terms=with_field(p, **kw))
    return np.array([getattr(sol.keypoints, k) for k in KEYS]), sol.converged


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_derivatives_match_finite_differences(small_grid, seed):
    term = (compression.tension_field(0.8, 0.02, 0.005, 0.15, 1e-6),)
    r, z = random_state(small_grid, seed)
    x = pack(r, z)
    E, g, hb = assembly.derivatives(r, z, small_grid, term)

    def energy(y):
        return assembly.energy(y[0::2], y[1::2], small_grid, term)

    def gradient(y):
        return assembly.gradient(y[0::2], y[1::2], small_grid, term)

    assert 0 < E < np.inf
    np.testing.assert_allclose(g, fd_gradient(energy, x), rtol=0, atol=1e-6 * np.max(np.abs(g)))
    H = assembly.band_to_dense(hb)
    np.testing.assert_allclose(H, fd_jacobian(gradient, x), rtol=0, atol=1e-6 * np.max(np.abs(H)))


def test_without_jamming_and_one_ratio_it_is_the_slack_regularization():
    material = DEFAULT_MATERIAL.replace(n_nodes=60)
    grid = make_grid(Patch(30.0, 0.7), material)
    r, z = random_state(grid, 5)
    c = material.compression_ratio
    field = compression.tension_field(0.7, c, c, 0.0, 0.0)
    assert assembly.energy(r, z, grid, (field,)) == pytest.approx(
        assembly.energy(r, z, grid, (compression.TERM,)), rel=1e-13)


def test_a_segment_below_the_jamming_stretch_is_outside_the_domain():
    grid = make_grid(Patch(30.0, 0.7), DEFAULT_MATERIAL.replace(n_nodes=60))
    r, z = grid.R.copy(), np.zeros(grid.n_nodes)
    r[10:] -= 0.6                          # segment 9: length 0.4 dR, stretch t below 0.35
    field = compression.tension_field(0.7, 0.01, 0.0, 0.5)
    assert assembly.energy(r, z, grid, (field,)) == np.inf
    assert np.isfinite(assembly.energy(r, z, grid, (compression.tension_field(0.7, 0.01, 0.0, 0.2),)))


def test_keypoints_converge_as_the_floor_goes_to_zero():
    """With a jamming stretch, a decade of the numerical floor (1e-5 -> 1e-6) moves no keypoint
    of the 25 calibration designs by 0.05 mm, and every solve certifies."""
    worst = np.zeros(len(KEYS))
    for d, p in CALIBRATION_DESIGNS:
        (a, ok_a), (b, ok_b) = keypoints(d, p, floor=1e-5), keypoints(d, p, floor=1e-6)
        assert ok_a and ok_b, (d, p)
        worst = np.maximum(worst, np.abs(a - b))
    assert np.all(worst < 0.05), dict(zip(KEYS, worst))


def test_without_jamming_the_bare_fabrics_stiffness_sets_h():
    """The contrast: with the barrier at zero length, h keeps falling as the bare fabric's
    compressive stiffness goes to zero (docs/model.md): no limit to converge to."""
    h3 = keypoints(90.0, 0.6, c_fab=1e-3, jam=0.0, floor=0.0)[0][0]
    h4 = keypoints(90.0, 0.6, c_fab=1e-4, jam=0.0, floor=0.0)[0][0]
    assert h3 - h4 > 2.0


@pytest.mark.parametrize("kwargs", [{"jam": 1.0}, {"jam": -0.1}, {"c_fab": -1.0}, {"floor": -1e-9}])
def test_invalid_parameters(kwargs):
    args = {"fill": 0.8, "c_emb": 0.01, "c_fab": 0.0, "jam": 0.5, "floor": 1e-6} | kwargs
    with pytest.raises(InvalidInputError, match="tension_field"):
        compression.tension_field(**args)
