"""The shell reference: exact derivatives, and agreement with the reduced model."""
import numpy as np
import pytest

from stitchswitch import DEFAULT_MATERIAL, Patch, solve
from stitchswitch.fem_reference.density import density
from stitchswitch.fem_reference.shell import ShellModel
from stitchswitch.reduced.model.keypoints import keypoints_from_profile


@pytest.mark.parametrize("hoop, nu", [(0.0, 0.0), (1.0, 0.3)])
def test_density_derivatives_match_finite_differences(hoop, nu):
    rng = np.random.default_rng(0)
    n = 9
    q = np.array([rng.uniform(1, 5, n), rng.uniform(0.3, 2, n), rng.uniform(-1.5, 0.2, n),
                  rng.uniform(-1, 1, n), rng.uniform(-1, 1, n)])
    S = rng.uniform(0.5, 4, n)
    coef = dict(lam=np.where(S < 2, 1.5, 1.0), k_r=1.0, k_theta=0.7, w_b=10.0, w_log=0.3,
                gamma=1.0, c=0.01, jam=0.6, c_jam=0.8, hoop=hoop, nu=nu)
    f, g, H = density(q, S, coef)
    l = np.hypot(q[1], q[2])
    assert np.any(l < 0.6 * coef["lam"]) and np.any(l > coef["lam"])    # jammed and taut points
    eps = 1e-6
    for k in range(5):
        dq = np.zeros_like(q)
        dq[k] = eps
        fp, gp, _ = density(q + dq, S, coef)
        fm, gm, _ = density(q - dq, S, coef)
        np.testing.assert_allclose(g[k], (fp - fm) / (2 * eps), rtol=1e-6, atol=1e-8)
        np.testing.assert_allclose(H[:, k], (gp - gm) / (2 * eps), rtol=1e-6, atol=1e-7)
    np.testing.assert_allclose(H, H.transpose(1, 0, 2), atol=1e-12)


@pytest.fixture(scope="module")
def small_model():
    patch = Patch(30.0, 0.9)
    model = ShellModel(patch, DEFAULT_MATERIAL.replace(n_nodes=80), elements_inside=8, growth=1.3)
    red = solve(patch, DEFAULT_MATERIAL)
    return model, model.start_from_profile(red.R_mm, red.r_mm, red.z_mm)


def test_assembled_jacobian_matches_finite_differences(small_model):
    model, x = small_model
    E, g, H = model.derivatives(x)
    assert E == pytest.approx(model.energy(x), rel=1e-12)
    rng = np.random.default_rng(1)
    for k in rng.choice(model.free, 8, replace=False):
        e = np.zeros_like(x)
        e[k] = 1e-6
        fd = (model.energy(x + e) - model.energy(x - e)) / 2e-6
        assert fd == pytest.approx(g[k], rel=1e-5, abs=1e-7)
        _, gp, _ = model.derivatives(x + e)
        _, gm, _ = model.derivatives(x - e)
        col = (gp - gm) / 2e-6
        np.testing.assert_allclose(H[:, [k]].toarray().ravel(), col, rtol=1e-5, atol=1e-6)


@pytest.mark.parametrize("d, p", [(40.0, 0.8), (90.0, 1.0)])
def test_reference_agrees_with_the_reduced_model(d, p):
    """At the default resolution: h within 5 % and r_a within 3 % of the reduced N = 300."""
    patch = Patch(d, p)
    red = solve(patch)
    model = ShellModel(patch, DEFAULT_MATERIAL, elements_inside=40)
    sol = model.solve(model.start_from_profile(red.R_mm, red.r_mm, red.z_mm))
    assert sol.converged and sol.residual <= 1e-9
    kp = keypoints_from_profile(*sol.sample())
    assert abs(kp.h_mm - red.keypoints.h_mm) <= 0.05 * red.keypoints.h_mm
    assert abs(kp.r_a_mm - red.keypoints.r_a_mm) <= 0.03 * red.keypoints.r_a_mm
    # the continuum energy of the reduced equilibrium: the reduced energy times N dR^2
    x_red = model.start_from_profile(red.R_mm, red.r_mm, red.z_mm)
    assert model.energy(x_red) == pytest.approx(red.energy * 300 * red.dr_mm ** 2, rel=0.05)


def test_hoop_bending_switch_stiffens_the_dome():
    patch = Patch(60.0, 0.8)
    red = solve(patch)
    plain = ShellModel(patch, DEFAULT_MATERIAL, elements_inside=30)
    hoop = ShellModel(patch, DEFAULT_MATERIAL, elements_inside=30, hoop_bending=True, poisson=0.3)
    x0 = plain.start_from_profile(red.R_mm, red.r_mm, red.z_mm)
    assert hoop.energy(x0) > plain.energy(x0)              # the extra term is positive here
    a, b = plain.solve(x0), hoop.solve(x0)
    assert a.converged and b.converged
    assert b.energy > a.energy
    assert not np.allclose(a.z_mm, b.z_mm, atol=1e-3)


def test_observed_convergence_rate_under_nested_refinement():
    """h and r_a of d = 90 mm, p = 1.0 over four nested meshes (3 refinements): the successive
    differences fall at first order (observed rates 1.09, 1.06 for h and 1.04, 0.91 for r_a),
    below the fourth order of smooth Hermite problems: the solution is not smooth (the
    tension-only kink and the fold outside the boundary are not mesh-aligned)."""
    patch = Patch(90.0, 1.0)
    red = solve(patch, DEFAULT_MATERIAL.replace(n_nodes=600, dr_max_mm=0.25))
    values = []
    for k in range(2, 6):
        model = ShellModel(patch, DEFAULT_MATERIAL, elements_inside=8, growth=1.25, refine=k)
        sol = model.solve(model.start_from_profile(red.R_mm, red.r_mm, red.z_mm), max_iter=100)
        assert sol.converged
        kp = keypoints_from_profile(*sol.sample())
        values.append((kp.h_mm, kp.r_a_mm))
    values = np.array(values)
    size = 0.5 ** np.arange(1, 4)                   # mesh size of each difference, relative
    for col in range(2):
        diffs = np.abs(np.diff(values[:, col]))
        rate = np.polyfit(np.log(size), np.log(diffs), 1)[0]
        assert abs(rate - 1.0) < 0.3, rate
        assert diffs[-1] < 0.005                     # mm: the finest meshes agree closely


# ----------------------------------------------------------------- prestretch continuation
from stitchswitch.errors import InvalidInputError  # noqa: E402
from stitchswitch.fem_reference import continuation  # noqa: E402

KEYPOINTS = ("h_mm", "r_a_mm", "z_a_mm", "r_b_mm", "z_b_mm")


def test_flat_sheet_is_the_stress_free_minimizer_at_zero_prestretch():
    model = ShellModel(Patch(40.0, 0.8), DEFAULT_MATERIAL, elements_inside=10, growth=1.3)
    assert model.prestretched(1.0) is model
    flat = model.prestretched(0.0)
    x = flat.flat_state()
    E, g, _ = flat.derivatives(x)
    assert E == pytest.approx(0.0, abs=1e-14)
    assert np.max(np.abs(g[flat.free])) < 1e-10              # round-off of the assembly
    assert flat.lowest_eigenvalue(x) > 0                   # a strict minimum (no seed needed)
    assert model.energy(x) > 1e-3                          # the design's prestretch loads it


def test_mirror_image_has_the_same_energy(small_model):
    """E(z) = E(-z): the symmetry the continuation's mirroring relies on."""
    model, x = small_model
    m = x.copy()
    m[model.n:] *= -1.0
    assert continuation.mirrored(model, m)[model.n] == pytest.approx(x[model.n])
    assert model.energy(m) == pytest.approx(model.energy(x), rel=1e-13)


def test_eigen_shift_newton_finds_the_same_equilibrium_from_the_reduced_start():
    patch = Patch(90.0, 1.0)
    red = solve(patch)
    model = ShellModel(patch, DEFAULT_MATERIAL, elements_inside=20, growth=1.16)
    x0 = model.start_from_profile(red.R_mm, red.r_mm, red.z_mm)
    a = model.solve(x0)
    b = model.solve(x0, globalization="eigen")
    assert a.converged and b.converged
    np.testing.assert_allclose(b.z_mm, a.z_mm, atol=1e-6)
    with pytest.raises(InvalidInputError, match="globalization"):
        model.solve(x0, globalization="trust")


@pytest.mark.parametrize("d, p", [(40.0, 0.8), (60.0, 1.0), (90.0, 0.8)])
def test_continuation_reaches_the_equilibrium_of_the_reduced_start(d, p, monkeypatch):
    """From the flat sheet, without the reduced model (it is disabled during the continuation),
    to the same local minimum as Newton from the reduced equilibrium: keypoints within 0.5 %."""
    import stitchswitch.reduced.solvers.solve as reduced_solve

    patch = Patch(d, p)
    red = solve(patch)
    model = ShellModel(patch, DEFAULT_MATERIAL, elements_inside=40)
    ref = continuation.solve_reference(model, "reduced", red)

    def forbidden(*args, **kwargs):
        raise AssertionError("the continuation must not use the reduced model")

    monkeypatch.setattr(reduced_solve, "solve", forbidden)
    result = continuation.prestretch_continuation(model)
    sol = result.solution
    assert sol.converged and sol.residual <= 1e-9
    assert result.lowest_eigenvalue > 0                   # a local minimum, not a saddle
    assert result.stages[0].t <= continuation.INITIAL_STEP and result.stages[-1].t == 1.0
    kp, kp_ref = keypoints_from_profile(*sol.sample()), keypoints_from_profile(*ref.sample())
    for k in KEYPOINTS:
        assert getattr(kp, k) == pytest.approx(getattr(kp_ref, k), rel=5e-3), k
    assert sol.energy == pytest.approx(ref.energy, rel=1e-9)


def test_unknown_start_is_rejected():
    model = ShellModel(Patch(40.0, 0.8), DEFAULT_MATERIAL, elements_inside=8, growth=1.3)
    with pytest.raises(InvalidInputError, match="start: 'flat'"):
        continuation.solve_reference(model, "flat")


def test_variant_terms_attribute_the_discretization_gap():
    """The same-energy check (``fem_reference.check``): the paper's first-order quadrature of
    the boundary ring puts r_a several times further from the reduced model's own continuum
    limit than the default trapezoid rule at N = 300."""
    from stitchswitch.fem_reference.check import check_design

    row = check_design(Patch(90.0, 1.0), start="reduced")
    assert abs(row.paper_indexing_300_rel["r_a_mm"]) > 3.0 * abs(row.at(300).rel["r_a_mm"])
