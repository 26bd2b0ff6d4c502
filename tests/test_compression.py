"""The compressive response (``terms/compression.py``, ``Material.c_emb, c_fab, jam,
compression_floor``): its derivatives, its limit cases, and the convergence of the keypoints as
its numerical floor goes to zero."""
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


def keypoints(d, p, **changes):
    sol = solve(Patch(d, p), DEFAULT_MATERIAL.replace(**changes))
    return np.array([getattr(sol.keypoints, k) for k in KEYS]), sol.converged


def grid_of(d=30.0, p=0.7, **changes):
    return make_grid(Patch(d, p), DEFAULT_MATERIAL.replace(n_nodes=60, **changes))


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_derivatives_match_finite_differences(seed):
    small_grid = grid_of(20.0, 0.8, c_emb=0.02, c_fab=0.005, jam=0.15)
    term = (compression.TERM,)
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


def test_the_energy_written_out_independently():
    """Per segment: k_r lambda R_{i+1} [c lambda^2 psi(t) + c_jam (j lambda - l)_+^2] / N, with c
    mixed by fill inside (c_emb p^2 + c_fab (1 - p^2)) and c_fab outside, plus the floor."""
    c_emb, c_fab, jam, c_jam, floor, p = 0.03, 0.004, 0.6, 0.7, 1e-4, 0.7
    grid = grid_of(30.0, p, c_emb=c_emb, c_fab=c_fab, jam=jam, c_jam=c_jam, compression_floor=floor)
    r, z = random_state(grid, 5)
    l = np.hypot(np.diff(r), np.diff(z))
    t = l / grid.lam
    psi = np.where(t < 1.0, 2.0 * (t - 1.0 - np.log(t)), 0.0)
    jammed = np.where(t < 1.0, np.maximum(jam * grid.lam - l, 0.0), 0.0)
    c = np.where(grid.inside, c_emb * p * p + c_fab * (1.0 - p * p), c_fab) + floor
    want = np.sum(grid.k_r * grid.lam * grid.R[1:] * (c * grid.lam ** 2 * psi + c_jam * jammed ** 2))
    assert np.min(t) < jam and np.max(t) > 1.0          # the state reaches every branch
    assert assembly.energy(r, z, grid, (compression.TERM,)) == pytest.approx(want / grid.n_nodes, rel=1e-12)


def test_past_the_jamming_stretch_the_knit_is_as_stiff_as_in_tension():
    """With c_jam = 1 the penalty mirrors the tension-only radial term at t = j: a segment
    shortened by x below j lambda costs what one stretched by x above lambda does (the other
    segments, the patch's compressed ones among them, are the same in both states)."""
    grid = grid_of(30.0, 0.7, c_fab=0.0, compression_floor=1e-12, jam=0.5, c_jam=1.0)
    r, z = np.arange(60, dtype=float), np.zeros(60)
    i = 50                                            # a bare segment, lambda = 1
    short, long_ = r.copy(), r.copy()
    short[i + 1:] -= 0.6                              # l = 0.4 = j - 0.1
    long_[i + 1:] += 0.1                              # l = 1.1 = 1 + 0.1
    radial = next(t for t in ALL_TERMS if t.name == "radial")
    e_short = assembly.energy(short, z, grid, (compression.TERM,)) - assembly.energy(r, z, grid, (compression.TERM,))
    e_long = assembly.energy(long_, z, grid, (radial,)) - assembly.energy(r, z, grid, (radial,))
    assert e_short == pytest.approx(e_long, rel=1e-6)


def test_zero_length_is_outside_the_domain():
    r = np.arange(60, dtype=float)
    r[10:] -= 1.0                                     # segment 9 has zero length
    assert assembly.energy(r, np.zeros(60), grid_of(), (compression.TERM,)) == np.inf


def test_keypoints_converge_as_the_floor_goes_to_zero():
    """With a jamming stretch, a decade of the numerical floor (1e-5 -> 1e-6) moves no keypoint
    of the 25 calibration designs by 0.05 mm, and every solve certifies."""
    worst = np.zeros(len(KEYS))
    for d, p in CALIBRATION_DESIGNS:
        (a, ok_a), (b, ok_b) = keypoints(d, p, compression_floor=1e-5), keypoints(d, p, compression_floor=1e-6)
        assert ok_a and ok_b, (d, p)
        worst = np.maximum(worst, np.abs(a - b))
    assert np.all(worst < 0.05), dict(zip(KEYS, worst))


def test_without_jamming_the_bare_fabrics_stiffness_sets_h():
    """The contrast: with the barrier at zero length, h keeps falling as the bare fabric's
    compressive stiffness goes to zero (docs/model.md): no limit to converge to."""
    (a, ok_a), (b, ok_b) = (keypoints(90.0, 0.6, c_fab=c, jam=0.0, compression_floor=1e-12)
                            for c in (1e-2, 1e-3))
    assert ok_a and ok_b
    assert a[0] - b[0] > 2.0


@pytest.mark.parametrize("changes, name", [({"jam": 1.0}, "jam"), ({"jam": -0.1}, "jam"),
                                           ({"c_fab": -1.0}, "c_fab"), ({"c_emb": 1.0}, "c_emb"),
                                           ({"compression_floor": 0.0}, "compression_floor"),
                                           ({"c_jam": -1.0}, "c_jam"),
                                           ({"jam": 0.0, "c_fab": 0.0}, "jam"),
                                           ({"c_jam": 0.0, "c_fab": 0.0}, "jam")])
def test_invalid_parameters(changes, name):
    with pytest.raises(InvalidInputError, match=f"^{name}: "):
        DEFAULT_MATERIAL.replace(**changes)
