"""The paper's discretization (section 4, "Discretization" and "Strain").

N_in = ceil((d / 2 eta) / dR_max), dR = (d / 2 eta) / N_in, node N_in on the embroidery
boundary (the printed rule: tested with the small-patch refinement switched off, ``LITERAL``;
the refinement N_in >= (N - 1) / domain_max_rb is tested on its own below); segment i inside
iff i < N_in; lambda = 1 + (eta - 1) p^2 and
k = k_emb p^2 + k_fab (1 - p^2) inside, lambda = 1 and k = k_fab outside; the bending hinge i
(node i+1) uses the weight of segment i.
"""
import dataclasses
import math
from fractions import Fraction

import numpy as np
import pytest

from stitchswitch.errors import InvalidInputError
from stitchswitch.reduced.model.discretization import Grid, make_grid, min_inside, n_inside
from stitchswitch.reduced.model.params import DEFAULT_MATERIAL as SHIPPED
from stitchswitch.reduced.model.params import Patch

# The printed rule: the domain may be any number of patch radii (no small-patch refinement).
DEFAULT_MATERIAL = SHIPPED.replace(domain_max_rb=1000.0)

# Materials with other pre-stretches and spacings than the paper's eta = 1.7, dR_max = 0.5 mm.
# n_nodes is large enough for every supported diameter.
MATERIALS = {
    "paper": DEFAULT_MATERIAL,
    "eta1.5_dr0.3": DEFAULT_MATERIAL.replace(eta=1.5, dr_max_mm=0.3, n_nodes=400),
    "eta1.3_dr0.7": DEFAULT_MATERIAL.replace(eta=1.3, dr_max_mm=0.7, n_nodes=300),
    "eta2.2_dr0.35": DEFAULT_MATERIAL.replace(eta=2.2, dr_max_mm=0.35, n_nodes=300),
    "eta1.7_dr0.1": DEFAULT_MATERIAL.replace(eta=1.7, dr_max_mm=0.1, n_nodes=1000),
}

# A material whose seven coefficients all differ, so that a swapped emb/fab or r/theta shows.
DISTINCT = DEFAULT_MATERIAL.replace(
    w_b_emb=7.0, w_b_fab=0.3, k_r_emb=3.0, k_r_fab=0.2, k_theta_emb=5.0, k_theta_fab=0.7)


def exact_n_inside(d, eta, dr_max):
    """ceil((d / 2 eta) / dR_max) in exact rational arithmetic on the decimal values."""
    ratio = Fraction(repr(d)) / (2 * Fraction(repr(eta))) / Fraction(repr(dr_max))
    return math.ceil(ratio)


def multiples_in_range(eta, dr_max):
    """Every k for which d = 2 eta dR_max k lies in the supported range [10, 150] mm."""
    step = 2 * Fraction(repr(eta)) * Fraction(repr(dr_max))
    return [k for k in range(1, 5000) if 10 <= step * k <= 150]


# ---------------------------------------------------------------------------------- N_in

@pytest.mark.parametrize("d", [10.0, 10.5, 12.34, 20.0, 33.3, 50.0, 77.7, 99.99, 120.0, 149.9, 150.0])
@pytest.mark.parametrize("name", list(MATERIALS))
def test_n_inside_is_the_ceiling(name, d):
    material = MATERIALS[name]
    expected = exact_n_inside(d, material.eta, material.dr_max_mm)
    assert n_inside(Patch(d, 0.5), material) == expected
    assert make_grid(Patch(d, 0.5), material).n_inside == expected


def test_n_inside_paper_values():
    # Hand-computed with eta = 1.7, dR_max = 0.5 mm: (d / 3.4) / 0.5 = d / 1.7.
    for d, expected in [(10.0, 6), (17.0, 10), (20.0, 12), (30.0, 18), (100.0, 59), (150.0, 89)]:
        assert n_inside(Patch(d, 1.0), DEFAULT_MATERIAL) == expected, d


@pytest.mark.parametrize("name", list(MATERIALS))
def test_exact_multiple_computed_adds_no_node(name):
    """d = 2 eta dR_max k computed in floating point: N_in must be k, not k + 1."""
    material = MATERIALS[name]
    ks = multiples_in_range(material.eta, material.dr_max_mm)
    assert ks
    for k in ks:
        d = 2 * material.eta * material.dr_max_mm * k
        assert n_inside(Patch(d, 0.7), material) == k, (d, k)


@pytest.mark.parametrize("name", list(MATERIALS))
def test_exact_multiple_decimal_literal_adds_no_node(name):
    """d written as the decimal literal of 2 eta dR_max k (e.g. 22.1 = 1.7 * 13, where the
    naive floating-point ratio is 13.000000000000002): N_in must be k."""
    material = MATERIALS[name]
    step = 2 * Fraction(repr(material.eta)) * Fraction(repr(material.dr_max_mm))
    for k in multiples_in_range(material.eta, material.dr_max_mm):
        d = float(step * k)
        assert n_inside(Patch(d, 0.7), material) == k, (d, k)
        assert make_grid(Patch(d, 0.7), material).n_inside == k, (d, k)


def test_known_round_off_cases():
    # These ratios come out just above an integer in floating point.
    for d, k in [(22.1, 13), (35.7, 21), (44.2, 26), (52.7, 31)]:
        assert d / (2 * 1.7) / 0.5 > k          # the round-off the guard must absorb
        assert n_inside(Patch(d, 1.0), DEFAULT_MATERIAL) == k


def test_just_above_a_multiple_adds_a_node():
    # 17 mm is exactly 10 nodes; a little more needs an 11th.
    assert n_inside(Patch(17.0, 1.0), DEFAULT_MATERIAL) == 10
    assert n_inside(Patch(17.001, 1.0), DEFAULT_MATERIAL) == 11
    assert n_inside(Patch(16.999, 1.0), DEFAULT_MATERIAL) == 10


# ------------------------------------------------------------------------------ spacing

def _diameters():
    rng = np.random.default_rng(12345)
    return [10.0, 150.0, 17.0, 22.1, 35.7] + list(rng.uniform(10.0, 150.0, 40))


@pytest.mark.parametrize("name", list(MATERIALS))
def test_spacing_bound_and_boundary_node(name):
    material = MATERIALS[name]
    for d in _diameters():
        grid = make_grid(Patch(d, 0.6), material)
        rest_radius = d / (2 * material.eta)
        # dR <= dR_max (up to round-off), and N_in is the smallest count achieving it.
        assert grid.dr_mm <= material.dr_max_mm * (1 + 1e-12), d
        assert (grid.n_inside - 1) * material.dr_max_mm < rest_radius * (1 + 1e-12), d
        # Node N_in lies exactly on the embroidery boundary.
        assert grid.n_inside * grid.dr_mm == pytest.approx(rest_radius, rel=1e-12, abs=0), d
        assert grid.R[grid.n_inside] * grid.dr_mm == pytest.approx(rest_radius, rel=1e-12, abs=0)
        # Uniform nodes R_i = i in dR units.
        assert grid.n_nodes == material.n_nodes
        np.testing.assert_array_equal(grid.R, np.arange(material.n_nodes, dtype=float))


# ---------------------------------------------------------------------- inside / outside

@pytest.mark.parametrize("d", [10.0, 22.1, 47.3, 150.0])
def test_segment_inside_iff_index_below_n_inside(d):
    grid = make_grid(Patch(d, 0.5), DEFAULT_MATERIAL)
    n = grid.n_nodes
    assert grid.inside.shape == (n - 1,)
    i = np.arange(n - 1)
    np.testing.assert_array_equal(grid.inside, i < grid.n_inside)
    # Both nodes of an inside segment lie in the closed disc R <= d / 2 eta (in dR units N_in),
    # and every outside segment has its outer node beyond the boundary.
    assert np.all(grid.R[1:][grid.inside] <= grid.n_inside)
    assert np.all(grid.R[1:][~grid.inside] > grid.n_inside)
    assert grid.inside[grid.n_inside - 1] and not grid.inside[grid.n_inside]
    assert grid.inside.sum() == grid.n_inside


@pytest.mark.parametrize("fill", [1e-3, 0.25, 0.5, 0.8, 1.0])
@pytest.mark.parametrize("d", [10.0, 35.7, 90.0])
def test_rest_metric(d, fill):
    for material in (DEFAULT_MATERIAL, DISTINCT.replace(eta=2.5), DISTINCT.replace(eta=1.2)):
        grid = make_grid(Patch(d, fill), material)
        n_in = grid.n_inside
        assert grid.lam.shape == (material.n_nodes - 1,)
        expected_inside = 1.0 + (material.eta - 1.0) * fill ** 2
        np.testing.assert_allclose(grid.lam[:n_in], expected_inside, rtol=1e-14, atol=0)
        np.testing.assert_array_equal(grid.lam[n_in:], 1.0)


def test_rest_metric_full_fill_is_the_pre_stretch():
    grid = make_grid(Patch(40.0, 1.0), DEFAULT_MATERIAL)
    np.testing.assert_allclose(grid.lam[:grid.n_inside], 1.7, rtol=1e-15)
    np.testing.assert_array_equal(grid.lam[grid.n_inside:], 1.0)


@pytest.mark.parametrize("fill", [1e-3, 0.3, 0.75, 1.0])
@pytest.mark.parametrize("d", [10.0, 52.7, 150.0])
def test_membrane_stiffnesses(d, fill):
    m = DISTINCT
    grid = make_grid(Patch(d, fill), m)
    n_in = grid.n_inside
    p2 = fill ** 2
    for arr, emb, fab in [(grid.k_r, m.k_r_emb, m.k_r_fab),
                          (grid.k_theta, m.k_theta_emb, m.k_theta_fab)]:
        assert arr.shape == (m.n_nodes - 1,)
        np.testing.assert_allclose(arr[:n_in], emb * p2 + fab * (1 - p2), rtol=1e-14, atol=0)
        np.testing.assert_array_equal(arr[n_in:], fab)


def test_full_fill_gives_embroidery_stiffness_inside():
    m = DISTINCT
    grid = make_grid(Patch(60.0, 1.0), m)
    n_in = grid.n_inside
    np.testing.assert_allclose(grid.k_r[:n_in], m.k_r_emb, rtol=1e-15)
    np.testing.assert_allclose(grid.k_theta[:n_in], m.k_theta_emb, rtol=1e-15)
    np.testing.assert_allclose(grid.w_b[:n_in], m.w_b_emb, rtol=1e-15)


@pytest.mark.parametrize("fill", [0.2, 0.9, 1.0])
@pytest.mark.parametrize("d", [10.0, 44.2, 150.0])
def test_bending_weight_per_hinge(d, fill):
    m = DISTINCT
    grid = make_grid(Patch(d, fill), m)
    n, n_in = m.n_nodes, grid.n_inside
    p2 = fill ** 2
    assert grid.w_b.shape == (n - 2,)
    seg_weight = np.where(np.arange(n - 1) < n_in, m.w_b_emb * p2 + m.w_b_fab * (1 - p2), m.w_b_fab)
    # Hinge i (at node i+1, between segments i and i+1) uses the weight of segment i.
    np.testing.assert_allclose(grid.w_b, seg_weight[:-1], rtol=1e-14, atol=0)
    # So the hinge on the boundary node N_in (hinge N_in - 1) is inside, the next one outside.
    inside_w = m.w_b_emb * p2 + m.w_b_fab * (1 - p2)
    assert grid.w_b[n_in - 1] == pytest.approx(inside_w, rel=1e-14)
    assert grid.w_b[n_in] == m.w_b_fab


def test_scalar_coefficients_are_passed_through():
    m = DISTINCT.replace(w_log=0.37, gamma_mm=4.5, c_emb=0.03, c_fab=0.002, jam=0.4,
                         compression_floor=1e-5)
    grid = make_grid(Patch(30.0, 0.5), m)
    assert grid.w_log == 0.37
    assert grid.gamma == pytest.approx(4.5 / grid.dr_mm, rel=1e-15)
    assert grid.jam == 0.4
    n_in = grid.n_inside
    np.testing.assert_allclose(grid.compression[:n_in], 0.03 * 0.25 + 0.002 * 0.75 + 1e-5, rtol=1e-14)
    np.testing.assert_allclose(grid.compression[n_in:], 0.002 + 1e-5, rtol=1e-14)
    assert grid.bending_scale == pytest.approx((0.5 / grid.dr_mm) ** 2, rel=1e-15)


# ---------------------------------------------------------------------------- read-only

def _arrays(grid):
    return {"lam": grid.lam, "k_r": grid.k_r, "k_theta": grid.k_theta, "w_b": grid.w_b,
            "compression": grid.compression}


def test_arrays_are_read_only():
    grid = make_grid(Patch(30.0, 0.5), DEFAULT_MATERIAL)
    for name, arr in _arrays(grid).items():
        assert not arr.flags.writeable, name
        with pytest.raises(ValueError):
            arr[0] = 123.0
    assert grid.lam[0] != 123.0


def test_grid_is_frozen():
    grid = make_grid(Patch(30.0, 0.5), DEFAULT_MATERIAL)
    with pytest.raises(dataclasses.FrozenInstanceError):
        grid.n_inside = 3
    with pytest.raises(dataclasses.FrozenInstanceError):
        grid.lam = np.ones(grid.n_nodes - 1)


# ---------------------------------------------------------------------- lambda scaling

@pytest.mark.parametrize("fill", [0.3, 1.0])
def test_with_lambda_scale(fill):
    grid = make_grid(Patch(40.0, fill), DISTINCT)
    flat = grid.with_lambda_scale(0.0)
    np.testing.assert_array_equal(flat.lam, 1.0)
    same = grid.with_lambda_scale(1.0)
    np.testing.assert_array_equal(same.lam, grid.lam)
    half = grid.with_lambda_scale(0.5)
    np.testing.assert_allclose(half.lam, 1.0 + 0.5 * (grid.lam - 1.0), rtol=1e-15)
    for scaled in (flat, same, half):
        assert isinstance(scaled, Grid)
        assert not scaled.lam.flags.writeable
        # Everything but lambda is unchanged.
        assert scaled.n_nodes == grid.n_nodes
        assert scaled.n_inside == grid.n_inside
        assert scaled.dr_mm == grid.dr_mm
        for name in ("k_r", "k_theta", "w_b", "compression"):
            np.testing.assert_array_equal(getattr(scaled, name), getattr(grid, name))
            assert not getattr(scaled, name).flags.writeable
        assert (scaled.w_log, scaled.gamma, scaled.jam) == (grid.w_log, grid.gamma, grid.jam)
    # The original is not modified.
    np.testing.assert_allclose(grid.lam[:grid.n_inside], 1.0 + 0.7 * fill ** 2, rtol=1e-14)


# -------------------------------------------------------------------- too many nodes

@pytest.mark.parametrize("n_nodes", [20, 50, 89, 90])
def test_patch_needing_more_nodes_than_allowed_raises(n_nodes):
    material = DEFAULT_MATERIAL.replace(n_nodes=n_nodes)
    patch = Patch(150.0, 0.5)                   # N_in = 89: no room for the outer fabric
    assert n_inside(patch, material) == 89
    with pytest.raises(InvalidInputError) as info:
        make_grid(patch, material)
    msg = str(info.value)
    assert "diameter_mm" in msg
    assert "150" in msg


def test_small_dr_max_raises_for_large_patch():
    material = DEFAULT_MATERIAL.replace(dr_max_mm=0.05)   # 150 mm needs 883 nodes
    with pytest.raises(InvalidInputError, match="diameter_mm"):
        make_grid(Patch(150.0, 1.0), material)


def test_largest_patch_fits_default_material():
    grid = make_grid(Patch(150.0, 1.0), DEFAULT_MATERIAL)
    assert grid.n_inside == 89
    assert grid.n_nodes == 300
    assert grid.n_nodes - 1 - grid.n_inside > 0     # there is fabric outside the patch


# ------------------------------------------------------------ small-patch refinement

@pytest.mark.parametrize("d", [10.0, 15.0, 20.0, 33.3, 50.0, 67.9, 68.1, 100.0, 150.0])
@pytest.mark.parametrize("n_nodes", [75, 300, 600])
def test_small_patches_get_a_finer_spacing_not_a_longer_domain(d, n_nodes):
    material = SHIPPED.replace(n_nodes=n_nodes, dr_max_mm=0.5 * 300 / n_nodes)
    grid = make_grid(Patch(d, 0.7), material)
    printed = exact_n_inside(d, material.eta, material.dr_max_mm)
    assert grid.n_inside == max(printed, min_inside(material))
    rb = d / (2 * material.eta)
    assert grid.dr_mm <= material.dr_max_mm * (1 + 1e-12)
    assert (n_nodes - 1) * grid.dr_mm <= material.domain_max_rb * rb * (1 + 1e-12)
    assert grid.n_inside * grid.dr_mm == pytest.approx(rb, rel=1e-12)


def test_shipped_rule_values():
    # N = 300, domain at most 7.5 R_b: at least ceil(299 / 7.5) = 40 nodes inside, which the
    # printed rule reaches from d = 2 eta dR_max 40 = 68 mm on.
    assert min_inside(SHIPPED) == 40
    for d, expected in [(10.0, 40), (30.0, 40), (67.9, 40), (68.0, 40), (68.1, 41), (100.0, 59)]:
        assert n_inside(Patch(d, 1.0), SHIPPED) == expected, d


def test_domain_ratio_is_validated():
    with pytest.raises(InvalidInputError, match="domain_max_rb"):
        SHIPPED.replace(domain_max_rb=1.5)
