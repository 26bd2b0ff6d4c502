"""The certified Newton solver: certificates, constraints, uniqueness, budgets, determinism."""
import numpy as np
import pytest

from stitchswitch import DEFAULT_MATERIAL, Patch, solve
from stitchswitch.reduced.model import assembly
from stitchswitch.reduced.model.discretization import make_grid
from stitchswitch.reduced.solvers import continuation, newton
from stitchswitch.reduced.solvers.constraints import admissible, kkt_residual
from stitchswitch.reduced.solvers.solve import DEFAULT_TOL

DESIGNS = [(15.0, 0.6), (25.0, 1.0), (40.0, 0.8), (70.0, 1.0), (100.0, 0.6)]


def _dr_units(sol):
    return sol.r_mm / sol.dr_mm, sol.z_mm / sol.dr_mm


@pytest.fixture(scope="module")
def solutions():
    return {dp: solve(Patch(*dp)) for dp in DESIGNS}


@pytest.mark.parametrize("dp", DESIGNS)
def test_certified_solution_satisfies_constraints_and_kkt(solutions, dp):
    sol = solutions[dp]
    assert sol.converged and sol.residual <= DEFAULT_TOL and sol.second_order is True
    r, z = _dr_units(sol)
    assert admissible(r, z, atol=1e-12)
    # the certificate, recomputed here from the gradient of the total energy
    grid = make_grid(Patch(*dp), DEFAULT_MATERIAL)
    _, g, hb = assembly.derivatives(r, z, grid)
    # The profile went through mm and back: a round-off of a few ulps in r and z, times the
    # Hessian (which grows like dR^-2 for the finely resolved small patches), may add to the
    # certificate: at most |H| times two ulps of every coordinate, row by row.
    ulps = np.empty(2 * r.size)
    ulps[0::2], ulps[1::2] = np.spacing(np.abs(r)), np.spacing(np.abs(z))
    roundtrip = (np.abs(assembly.band_to_dense(hb)) @ (2.0 * ulps)).max()
    recomputed = kkt_residual(g[0::2], g[1::2], z[:-1] - z[1:])
    assert recomputed <= DEFAULT_TOL + roundtrip
    assert recomputed == pytest.approx(sol.residual, abs=5e-12 + roundtrip)
    # and a finite-difference check that r is stationary (independent of the analytic gradient)
    # (h is small: a segment resting near its jamming stretch has a large third derivative)
    for i in (1, grid.n_inside // 2, grid.n_inside, grid.n_inside + 3, grid.n_nodes - 1):
        h = 1e-7
        rp, rm = r.copy(), r.copy()
        rp[i] += h
        rm[i] -= h
        fd = (assembly.energy(rp, z, grid) - assembly.energy(rm, z, grid)) / (2 * h)
        assert abs(fd) < 1e-6      # central differences straddle the C1 kinks of the max()


@pytest.mark.parametrize("dp", [(40.0, 0.8), (70.0, 1.0)])
def test_same_equilibrium_from_different_admissible_starts(solutions, dp):
    sol = solutions[dp]
    grid = make_grid(Patch(*dp), DEFAULT_MATERIAL)
    r_star, z_star = _dr_units(sol)
    rng = np.random.default_rng(1)
    starts = []
    s = np.clip(grid.R / grid.n_inside, 0, 1)
    for amp in (0.03, 0.07):                                  # other seed bumps
        z = amp * grid.n_inside * (1 - s * s) ** 2
        z[0] = z[1]
        starts.append((grid.R.copy(), z))
    for _ in range(2):                                        # smooth perturbations of the solution
        bump = np.sin(np.pi * grid.R / grid.R[-1] * rng.integers(1, 6)) * rng.uniform(0.05, 0.2)
        r = r_star + bump * (grid.R > 0)
        drops = np.maximum(z_star[:-1] - z_star[1:] + rng.uniform(0, 0.02, grid.n_nodes - 1), 0)
        drops[0] = 0
        starts.append((r, np.concatenate([np.cumsum(drops[::-1])[::-1], [0.0]])))
    for r0, z0 in starts:
        res = newton.minimize(grid, r0, z0, tol=DEFAULT_TOL, max_iter=300)
        assert res.converged and res.second_order
        assert res.energy == pytest.approx(sol.energy, rel=1e-9)
        assert np.max(np.abs(res.r * grid.dr_mm - sol.r_mm)) < 1e-5
        assert np.max(np.abs(res.z * grid.dr_mm - sol.z_mm)) < 1e-5


def test_too_small_budget_fails_loudly():
    sol = solve(Patch(60.0, 0.9), max_iter=3)
    assert sol.converged is False
    assert sol.residual > sol.tol
    assert sol.iterations <= 3
    assert "budget" in sol.message
    assert sol.as_dict()["converged"] is False


def test_deterministic_bit_identical():
    a, b = solve(Patch(47.3, 0.77)), solve(Patch(47.3, 0.77))
    assert np.array_equal(a.r_mm, b.r_mm) and np.array_equal(a.z_mm, b.z_mm)
    assert a.energy == b.energy and a.iterations == b.iterations


def test_warm_start_from_neighbour_reaches_the_cold_solution(solutions):
    neighbour = solve(Patch(42.0, 0.82))
    warm = solve(Patch(40.0, 0.8), warm_start=neighbour)
    cold = solutions[(40.0, 0.8)]
    assert warm.converged
    assert warm.energy == pytest.approx(cold.energy, rel=1e-9)
    assert warm.keypoints.h_mm == pytest.approx(cold.keypoints.h_mm, abs=1e-5)


def test_saddle_is_left_along_negative_curvature():
    """The exactly flat state is stationary for every design (z -> -z symmetry); for one that
    buckles it is a saddle, and the solver must not stop there."""
    grid = make_grid(Patch(40.0, 0.8), DEFAULT_MATERIAL)
    flat_E = assembly.energy(grid.R, np.zeros(grid.n_nodes), grid)
    res = newton.minimize(grid, grid.R.copy(), np.zeros(grid.n_nodes), tol=1e-9, max_iter=300)
    assert res.converged and res.second_order
    assert res.energy < flat_E
    assert res.z[0] * grid.dr_mm > 5.0                          # popped up, not down


def test_zero_fill_limit_is_flat_and_stress_free():
    sol = solve(Patch(40.0, 1e-6))
    assert sol.converged
    assert sol.keypoints.h_mm < 1e-6
    assert sol.energy < 1e-15
    np.testing.assert_allclose(sol.r_mm, sol.R_mm, atol=1e-9)


def test_newton_energy_not_above_adam_baseline():
    patch = Patch(30.0, 0.9)
    newton_sol = solve(patch)
    adam_sol = solve(patch, solver="adam", max_iter=3000)
    assert adam_sol.converged is False                           # and it says so
    assert newton_sol.energy <= adam_sol.energy * (1 + 1e-9)


def test_release_continuation_fallback_converges():
    grid = make_grid(Patch(60.0, 0.7), DEFAULT_MATERIAL)
    res, used = continuation.release(grid, tol=1e-9, max_iter=400)
    assert res.converged and used <= 400
    assert admissible(res.r, res.z, atol=1e-12)


def _min_stretch(sol):
    grid = make_grid(sol.patch, sol.material)
    return float(np.min(np.hypot(np.diff(sol.r_mm), np.diff(sol.z_mm)) / sol.dr_mm / grid.lam))


def test_compressive_response_inactive_where_every_segment_is_taut():
    """A fully taut equilibrium does not feel the compressive response: it is a local
    minimizer of the printed model itself, with the same keypoints for every c_emb and jam."""
    sols = [solve(Patch(70.0, 1.0), DEFAULT_MATERIAL.replace(c_emb=c, jam=j))
            for c, j in ((0.003, 0.3), (0.01, 0.5), (0.03, 0.7))]
    for s in sols:
        assert s.converged and _min_stretch(s) >= 1.0 - 1e-9
    for s in sols[1:]:
        assert s.energy == pytest.approx(sols[0].energy, rel=1e-10)
        # h to the default material's soft mode (tests/test_default_map.py: energies equal to
        # round-off while h moves up to 3.3e-5 mm)
        assert s.keypoints.h_mm == pytest.approx(sols[0].keypoints.h_mm, abs=1e-4)
        assert s.keypoints.r_a_mm == pytest.approx(sols[0].keypoints.r_a_mm, abs=1e-6)


def test_without_jamming_a_vanishing_compressive_stiffness_collapses_slack_segments():
    """The printed model's limit: with no jamming stretch and one compressive ratio c for mats
    and knit alike, as c -> 0 the shortest segment shrinks roughly in proportion to c and the
    dome flattens, the excess length hiding in collapsed node-scale folds (docs/model.md)."""
    cs = (0.01, 0.003, 0.001, 0.0003)
    sols = [solve(Patch(90.0, 0.6), DEFAULT_MATERIAL.replace(c_emb=c, c_fab=c, jam=0.0,
                                                            compression_floor=1e-12)) for c in cs]
    assert all(s.converged for s in sols)
    stretch = [_min_stretch(s) for s in sols]
    h = [s.keypoints.h_mm for s in sols]
    assert all(a > b for a, b in zip(stretch, stretch[1:]))
    assert stretch[-1] < 0.05
    assert all(a > b for a, b in zip(h, h[1:]))
    assert h[0] > 8.0 and h[-1] < 0.1 * h[0]


def test_default_material_shows_the_papers_qualitative_findings():
    def kp(d, p):
        return solve(Patch(d, p)).keypoints

    assert kp(15.0, 0.6).h_mm < 1.0                                   # small, sparse: near flat
    heights = [kp(d, 0.8).h_mm for d in (20.0, 40.0, 60.0, 90.0)]
    assert all(a < b for a, b in zip(heights, heights[1:]))          # h grows with d
    big = kp(90.0, 1.0)
    assert 12.0 <= big.h_mm <= 30.0                                   # the paper's magnitude
    assert big.b_rule == "neck" and big.r_b_mm < big.r_a_mm           # overhanging mushroom
    assert kp(40.0, 0.6).b_rule != "neck"                             # lower fill: no overhang


def test_custom_terms_need_newton():
    from stitchswitch import InvalidInputError
    from stitchswitch.reduced.model.terms import ALL_TERMS

    with pytest.raises(InvalidInputError, match="terms"):
        solve(Patch(40.0, 0.8), solver="adam", terms=ALL_TERMS)
    a, b = solve(Patch(40.0, 0.8)), solve(Patch(40.0, 0.8), terms=ALL_TERMS)
    assert a.energy == b.energy


def test_solve_runs_on_one_blas_thread_and_restores_the_callers_setting(monkeypatch):
    from threadpoolctl import threadpool_info

    from stitchswitch.reduced.solvers import newton_loop

    seen = []
    real = newton_loop.fused_iterate

    def spy(*args):
        seen.append(max((p["num_threads"] for p in threadpool_info() if p["user_api"] == "blas"),
                        default=1))
        return real(*args)

    import scipy.linalg  # noqa: F401  (its OpenBLAS loaded, as after any solve: the list is complete)
    before = [(p["filepath"], p["num_threads"]) for p in threadpool_info()]
    monkeypatch.setattr(newton_loop, "fused_iterate", spy)
    solve(Patch(40.0, 0.8))
    assert seen and set(seen) == {1}
    assert [(p["filepath"], p["num_threads"]) for p in threadpool_info()] == before


def test_one_thread_nests_and_restores_the_setting_once_the_outer_block_ends():
    """A loop holds the limit once around many solves: the solves' own blocks inside it keep it
    and do not restore the caller's setting early."""
    from threadpoolctl import threadpool_info, threadpool_limits

    from stitchswitch.blas import one_thread

    def blas_threads():
        return max((p["num_threads"] for p in threadpool_info() if p["user_api"] == "blas"),
                   default=1)

    with threadpool_limits(limits=2, user_api="blas"):
        outside = blas_threads()
        with one_thread():
            with one_thread():
                assert blas_threads() == 1
            assert blas_threads() == 1
            solve(Patch(40.0, 0.8))
            assert blas_threads() == 1
        assert blas_threads() == outside
