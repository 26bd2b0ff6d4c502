"""Finite-difference checks of every term's gradient and Hessian, and the energy's invariances."""
import numpy as np
import pytest

from stitchswitch.reduced.model import assembly
from stitchswitch.reduced.model.discretization import make_grid
from stitchswitch.reduced.model.params import DEFAULT_MATERIAL, Patch
from stitchswitch.reduced.model.terms import ALL_TERMS, hardening

from helpers import fd_gradient as _fd_gradient
from helpers import fd_jacobian, random_state
from helpers import pack as _pack

TERMS = {t.__name__.rsplit(".", 1)[1]: t for t in ALL_TERMS}



@pytest.mark.parametrize("name", sorted(TERMS))
@pytest.mark.parametrize("seed", [0, 1, 2])
def test_gradient_and_hessian_match_finite_differences(small_grid, name, seed):
    term = (TERMS[name],)
    r, z = random_state(small_grid, seed)
    lengths = np.hypot(np.diff(r), np.diff(z))
    assert np.any(lengths < small_grid.lam) and np.any(lengths > small_grid.lam)   # slack and taut
    E, g, hb = assembly.derivatives(r, z, small_grid, term)

    def energy(x):
        return assembly.energy(x[0::2], x[1::2], small_grid, term)

    def gradient(x):
        return assembly.gradient(x[0::2], x[1::2], small_grid, term)

    x = _pack(r, z)
    assert E == pytest.approx(energy(x), rel=1e-12, abs=1e-300)
    assert E > 0
    g_fd = _fd_gradient(energy, x)
    scale = np.max(np.abs(g))
    assert scale > 0
    np.testing.assert_allclose(g, g_fd, rtol=0, atol=1e-6 * scale)
    H = assembly.band_to_dense(hb)
    H_fd = fd_jacobian(gradient, x)
    np.testing.assert_allclose(H, H_fd, rtol=0, atol=1e-6 * np.max(np.abs(H)))


def test_total_gradient_and_hessian(small_grid):
    r, z = random_state(small_grid, 7)
    x = _pack(r, z)
    _, g, hb = assembly.derivatives(r, z, small_grid)
    g_fd = _fd_gradient(lambda y: assembly.energy(y[0::2], y[1::2], small_grid), x)
    np.testing.assert_allclose(g, g_fd, rtol=0, atol=1e-6 * np.max(np.abs(g)))
    H_fd = fd_jacobian(lambda y: assembly.gradient(y[0::2], y[1::2], small_grid), x)
    H = assembly.band_to_dense(hb)
    np.testing.assert_allclose(H, H_fd, rtol=0, atol=1e-6 * np.max(np.abs(H)))


def test_hessian_is_banded(small_grid):
    """Only neighbouring nodes couple: nothing beyond half-bandwidth 5 in interleaved dofs."""
    r, z = random_state(small_grid, 3)
    x = _pack(r, z)
    H_fd = fd_jacobian(lambda y: assembly.gradient(y[0::2], y[1::2], small_grid), x)
    i, j = np.indices(H_fd.shape)
    assert np.max(np.abs(H_fd[np.abs(i - j) > 5])) < 1e-7


@pytest.mark.parametrize("seed", [0, 1])
def test_energy_invariant_under_reflection_and_rigid_shift(small_grid, seed):
    r, z = random_state(small_grid, seed)
    E = assembly.energy(r, z, small_grid)
    assert assembly.energy(r, -z, small_grid) == pytest.approx(E, rel=1e-13)
    assert assembly.energy(r, z + 3.7, small_grid) == pytest.approx(E, rel=1e-13)
    _, g, _ = assembly.derivatives(r, z, small_grid)
    assert abs(np.sum(g[1::2])) < 1e-10 * np.max(np.abs(g))     # no net force along z


def test_zero_fill_limit_has_zero_energy_flat():
    grid = make_grid(Patch(40.0, 1e-9), DEFAULT_MATERIAL)
    r, z = grid.R.copy(), np.zeros(grid.n_nodes)
    assert assembly.energy(r, z, grid) < 1e-30
    assert np.max(np.abs(assembly.gradient(r, z, grid))) < 1e-15


def test_energy_is_infinite_outside_domain(small_grid):
    r, z = random_state(small_grid, 0)
    folded = r.copy()
    folded[5] = folded[4]                       # a zero-length segment
    z_f = z.copy()
    z_f[5] = z_f[4]
    assert assembly.energy(folded, z_f, small_grid) == np.inf
    negative = r.copy()
    negative[3] = -1.0
    assert assembly.energy(negative, z, small_grid) == np.inf


def test_hardening_sign_and_continuation():
    """The corrected log term: zero with zero slope at rest, convex, C2 past the cutoff."""
    gamma = 3.0
    v, d1, d2 = hardening.h(np.array([0.0]), gamma)
    assert v[0] == 0.0 and d1[0] == 0.0 and d2[0] == pytest.approx(1 / gamma)
    e = np.linspace(-5.0, 2.5 * gamma, 2001)
    v, d1, d2 = hardening.h(e, gamma)
    assert np.all(d2 > 0) and np.all(v >= 0) and np.all(np.isfinite(v))
    # the printed form f(e) = (e - g) log((g - e)/g) - e is the negative: concave, rewards stretch
    inside = e < gamma * 0.9
    printed = (e[inside] - gamma) * np.log((gamma - e[inside]) / gamma) - e[inside]
    np.testing.assert_allclose(v[inside], -printed, rtol=1e-12, atol=1e-12)
    es = (1 - hardening.CUTOFF) * gamma
    below = hardening.h(np.array([es - 1e-9]), gamma)
    above = hardening.h(np.array([es + 1e-9]), gamma)
    for lo, hi in zip(below, above):
        assert hi[0] == pytest.approx(lo[0], rel=1e-6)
