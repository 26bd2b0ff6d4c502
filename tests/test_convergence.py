"""Observed convergence order of the reduced model in the node count N, against theory.

The domain is held fixed (dR_max = 0.5 mm x 300 / N, so the spacing halves as N doubles) and
the order is fitted from three refinements: p = log2(|q_N - q_2N| / |q_2N - q_4N|). On designs
whose equilibrium is taut everywhere (the solution is smooth), the paper's indexing of the
boundary node's ring is a first-order quadrature and the trapezoid rule (``boundary_ring``) a
second-order one, for r_a and for h. On designs with slack segments the trapezoid rule still
makes r_a converge faster than first order, while h converges erratically (the kinks of the
tension-only membrane and of the jamming penalty move across nodes as N changes); docs/model.md
reports the measured orders (scripts/study_convergence.py).
"""
import math

import numpy as np
import pytest

from stitchswitch import DEFAULT_MATERIAL, Patch, solve
from stitchswitch.reduced.model import assembly
from stitchswitch.reduced.model.discretization import make_grid
from stitchswitch.reduced.model.terms import ALL_TERMS, boundary_ring
from stitchswitch.reduced.model.terms.hardening import h
from stitchswitch.reduced.model.terms.variants import PAPER_INDEXING

from helpers import fd_gradient, fd_jacobian, pack, random_state

TAUT_DESIGNS = [(90.0, 1.0), (70.0, 1.0), (60.0, 0.9)]
SLACK_DESIGNS = [(40.0, 0.8), (90.0, 0.6)]
LEVELS = (150, 300, 600)


def observed_order(values) -> float:
    a, b, c = values
    return math.log2(abs(a - b) / abs(b - c))


def by_level(d, p, terms, key="r_a_mm"):
    out = []
    for n in LEVELS:
        material = DEFAULT_MATERIAL.replace(n_nodes=n, dr_max_mm=0.5 * 300 / n)
        sol = solve(Patch(d, p), material, terms=terms)
        assert sol.converged
        out.append(getattr(sol.keypoints, key))
    return out


def r_a_by_level(d, p, terms):
    return by_level(d, p, terms)


def min_stretch(d, p) -> float:
    sol = solve(Patch(d, p))
    lam = make_grid(sol.patch, sol.material).lam
    return float(np.min(np.hypot(np.diff(sol.r_mm), np.diff(sol.z_mm)) / sol.dr_mm / lam))


@pytest.mark.parametrize("d, p", TAUT_DESIGNS)
def test_printed_boundary_quadrature_is_first_order(d, p):
    assert observed_order(r_a_by_level(d, p, PAPER_INDEXING)) == pytest.approx(1.0, abs=0.2)


@pytest.mark.parametrize("d, p", TAUT_DESIGNS)
def test_trapezoid_boundary_quadrature_is_second_order(d, p):
    values = r_a_by_level(d, p, None)             # the default
    assert observed_order(values) == pytest.approx(2.0, abs=0.35)
    # and the error at N = 300 is a small fraction of the printed rule's
    printed = r_a_by_level(d, p, PAPER_INDEXING)
    assert abs(values[1] - values[2]) < 0.2 * abs(printed[1] - printed[2])


@pytest.mark.parametrize("d, p", TAUT_DESIGNS)
def test_h_converges_at_second_order_on_taut_designs(d, p):
    assert min_stretch(d, p) >= 1.0 - 1e-9                    # the equilibrium is taut: smooth
    assert observed_order(by_level(d, p, None, "h_mm")) > 1.7


@pytest.mark.parametrize("d, p", SLACK_DESIGNS)
def test_r_a_converges_faster_than_first_order_on_slack_designs(d, p):
    """Measured orders 2.05 (d 40, p 0.8) and 1.50 (d 90, p 0.6) against 1.0 for the printed
    rule (docs/model.md); h converges erratically there and is not asserted."""
    assert min_stretch(d, p) < 0.5                            # segments slack down to the jam
    assert observed_order(by_level(d, p, None)) > 1.3
    assert observed_order(by_level(d, p, PAPER_INDEXING)) == pytest.approx(1.0, abs=0.2)


@pytest.mark.parametrize("seed", [0, 1])
def test_boundary_ring_derivatives_match_finite_differences(small_grid, seed):
    r, z = random_state(small_grid, seed)
    x = pack(r, z)
    terms = (boundary_ring.TERM,)
    _, g, hb = assembly.derivatives(r, z, small_grid, terms)

    def energy(y):
        return assembly.energy(y[0::2], y[1::2], small_grid, terms)

    def gradient(y):
        return assembly.gradient(y[0::2], y[1::2], small_grid, terms)

    np.testing.assert_allclose(g, fd_gradient(energy, x), rtol=0, atol=1e-6 * np.max(np.abs(g)))
    H = assembly.band_to_dense(hb)
    np.testing.assert_allclose(H, fd_jacobian(gradient, x), rtol=0, atol=1e-6 * np.max(np.abs(H)))


def test_trapezoid_total_is_the_trapezoid_rule():
    """The hoop and hardening energy of the default terms, written out independently: every
    node's ring with its segment's values, but the boundary node half inside, half outside."""
    material = DEFAULT_MATERIAL.replace(n_nodes=60, w_log=0.5, gamma_mm=1.0)
    grid = make_grid(Patch(30.0, 0.8), material)
    rng = np.random.default_rng(3)
    R = grid.R
    r = R * (1.0 + rng.uniform(-0.05, 0.3, R.size))
    r[0] = 0.0
    z = np.linspace(2.0, 0.0, R.size)
    n, N = grid.n_inside, grid.n_nodes

    def ring(j, side):                    # side: the segment whose values node j takes
        lam, k = grid.lam[side], grid.k_theta[side]
        eps = r[j] - lam * R[j]
        return (k * eps ** 2 / (lam * R[j]) + grid.w_log * h(eps, grid.gamma)[0]) / N

    want = sum(ring(j, j - 1) for j in range(1, N) if j != n) + 0.5 * (ring(n, n - 1) + ring(n, n))
    rings = tuple(t for t in ALL_TERMS if t.name in ("circumferential", "hardening", "boundary_ring"))
    assert len(rings) == 3
    got = assembly.energy(r, z, grid, rings)
    assert got == pytest.approx(float(want), rel=1e-12)
