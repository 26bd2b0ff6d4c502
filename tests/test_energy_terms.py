"""Finite-difference checks of every term's gradient and Hessian (the model's and the extra
terms the discovery effects add), the energy's invariances, and the term protocol."""
import dataclasses

import numpy as np
import pytest

from stitchswitch.errors import InvalidInputError
from stitchswitch.reduced.model import assembly
from stitchswitch.reduced.model.discretization import make_grid
from stitchswitch.reduced.model.params import DEFAULT_MATERIAL, Patch
from stitchswitch.reduced.model.terms import ALL_TERMS, bending, hardening
from stitchswitch.reduced.model.terms.extra import gravity, hoop_bending, natural_curvature

from helpers import fd_gradient as _fd_gradient
from helpers import fd_jacobian, random_state
from helpers import pack as _pack

TERMS = {t.name: t for t in ALL_TERMS}


def _assembled_and_differenced(grid, terms, r, z):
    """(E, gradient, dense Hessian) of ``terms`` at (r, z) from the assembly, and the same by
    central finite differences (the energy itself, of the energy, of the gradient)."""
    E, g, hb = assembly.derivatives(r, z, grid, terms)
    x = _pack(r, z)

    def energy(y):
        return assembly.energy(y[0::2], y[1::2], grid, terms)

    def gradient(y):
        return assembly.gradient(y[0::2], y[1::2], grid, terms)

    return (E, g, assembly.band_to_dense(hb)), (energy(x), _fd_gradient(energy, x), fd_jacobian(gradient, x))


@pytest.mark.parametrize("name", sorted(TERMS))
@pytest.mark.parametrize("seed", [0, 1, 2])
def test_gradient_and_hessian_match_finite_differences(small_grid, name, seed):
    term = (TERMS[name],)
    r, z = random_state(small_grid, seed)
    lengths = np.hypot(np.diff(r), np.diff(z))
    assert np.any(lengths < small_grid.lam) and np.any(lengths > small_grid.lam)   # slack and taut
    (E, g, H), (E_x, g_fd, H_fd) = _assembled_and_differenced(small_grid, term, r, z)
    assert E == pytest.approx(E_x, rel=1e-12, abs=1e-300)
    assert E > 0 if name != "boundary_ring" else E != 0      # the ring's correction is signed
    scale = np.max(np.abs(g))
    assert scale > 0
    np.testing.assert_allclose(g, g_fd, rtol=0, atol=1e-6 * scale)
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


EXTRA_TERMS = {
    "hardening": hardening.with_weight(0.7, 1.0),
    "hoop_bending": hoop_bending.term(2.5),
    "natural_curvature_pos": natural_curvature.term(0.08, 0.8),
    "natural_curvature_neg": natural_curvature.term(-0.15, 1.0),
    "gravity": gravity.term(0.3, 0.8, 2.0),
}


@pytest.mark.parametrize("name", sorted(EXTRA_TERMS))
@pytest.mark.parametrize("seed", [0, 1])
def test_extra_term_derivatives_match_finite_differences(small_grid, name, seed):
    term = (EXTRA_TERMS[name],)
    r, z = random_state(small_grid, seed)
    (E, g, H), (E_x, g_fd, H_fd) = _assembled_and_differenced(small_grid, term, r, z)
    assert E == pytest.approx(E_x, rel=1e-12)
    assert E != 0.0
    scale = np.max(np.abs(g))
    assert scale > 0
    np.testing.assert_allclose(g, g_fd, rtol=0, atol=1e-6 * scale)
    np.testing.assert_allclose(H, H_fd, rtol=0, atol=1e-6 * max(np.max(np.abs(H_fd)), 1e-12))


def test_hoop_bending_is_the_shell_references_hoop_term():
    """On a smooth cone-like profile, H = 1 matches B z'^2 / (l r) integrated (B = w_b s / 8)."""
    grid = make_grid(Patch(60.0, 1.0), DEFAULT_MATERIAL)
    R = grid.R
    r = 1.3 * R
    z = 5.0 * np.exp(-(R / 40.0) ** 2)
    E = hoop_bending.term(1.0).energy(r, z, hoop_bending.term(1.0).coefficients(grid))
    mid = 0.5 * (R[1:] + R[:-1])
    zp = -5.0 * 2 * mid / 1600.0 * np.exp(-(mid / 40.0) ** 2)
    l = np.hypot(1.3, zp)
    w = hoop_bending.segment_weights(grid)
    continuum = np.sum(w * zp ** 2 / (l * 1.3 * mid)) / grid.n_nodes
    assert E == pytest.approx(continuum, rel=2e-3)


def test_natural_curvature_completes_the_square():
    """bending + natural_curvature = w rho^2/D (T - T0)^2 per inside hinge."""
    grid = make_grid(Patch(20.0, 0.9), DEFAULT_MATERIAL.replace(n_nodes=40))
    r, z = random_state(grid, 5)
    term = natural_curvature.term(0.1, 0.9)
    w, t0 = term.coefficients(grid)
    total = bending.energy(r, z, bending.coefficients(grid)) + term.energy(r, z, (w, t0))
    expected = 0.0
    wb = bending.coefficients(grid)[0]
    for i in range(grid.n_nodes - 2):
        a = np.array([r[i + 1] - r[i], z[i + 1] - z[i]])
        b = np.array([r[i + 2] - r[i + 1], z[i + 2] - z[i + 1]])
        T = (a[0] * b[1] - a[1] * b[0]) / (np.linalg.norm(a) * np.linalg.norm(b) + a @ b)
        D = 0.5 * (r[i] + r[i + 1]) * np.linalg.norm(a) + 0.5 * (r[i + 1] + r[i + 2]) * np.linalg.norm(b)
        A = r[i + 1] ** 2 / D
        expected += wb[i] * A * T ** 2 + w[i] * A * (t0[i] ** 2 - 2 * t0[i] * T)
        if w[i] == wb[i]:   # strictly inside: a perfect square
            assert wb[i] * A * (T - t0[i]) ** 2 == pytest.approx(
                wb[i] * A * T ** 2 + w[i] * A * (t0[i] ** 2 - 2 * t0[i] * T), rel=1e-12)
    assert total == pytest.approx(expected, rel=1e-12)
    assert np.count_nonzero(w) == grid.n_inside      # inside hinges plus the boundary hinge


def test_terms_are_checked_when_made_and_assembled(small_grid):
    """A term's stencil fits the Hessian's band; the assembly takes ``Term`` objects only."""
    with pytest.raises(InvalidInputError, match="stencil 4"):
        dataclasses.replace(bending.TERM, stencil=4)
    with pytest.raises(InvalidInputError, match="offset -1"):
        dataclasses.replace(bending.TERM, offset=-1)
    with pytest.raises(InvalidInputError, match="is not a Term"):
        assembly.Model(small_grid, (bending,))
