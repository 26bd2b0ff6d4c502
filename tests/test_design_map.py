"""The design map: building, exact agreement with direct solves, interpolation, domain, I/O."""
import numpy as np
import pytest

from stitchswitch import DEFAULT_MATERIAL, InvalidInputError, Patch, solve
from stitchswitch.reduced.design_space import precompute
from stitchswitch.reduced.design_space import smoothness as map_check
from stitchswitch.reduced.design_space import storage as map_io
from stitchswitch.reduced.design_space.design_map import FLAG_ONSET, FLAG_SMOOTH, FLAG_UNRESOLVED, KEYPOINTS
from stitchswitch.reduced.solvers.solve import DEFAULT_TOL


@pytest.fixture(scope="module")
def small_map():
    return precompute.build(DEFAULT_MATERIAL, np.arange(40.0, 45.0), np.round(np.arange(0.70, 0.745, 0.01), 2))


def test_grid_points_are_direct_solves(small_map):
    """Warm-started along the fill (the default), the map meets the direct solves to the
    solver's tolerance; cold-started, it is them exactly."""
    cold = precompute.build(DEFAULT_MATERIAL, small_map.diameter_mm, small_map.fill,
                            warm_start=False)
    for i, j in [(0, 0), (2, 3), (4, 4)]:
        sol = solve(Patch(small_map.diameter_mm[i], small_map.fill[j]))
        assert small_map.h_mm[i, j] == pytest.approx(sol.keypoints.h_mm, abs=1e-6)
        assert small_map.residual[i, j] <= DEFAULT_TOL
        np.testing.assert_allclose(small_map.z_prof_mm[i, j], sol.z_mm, atol=1e-5)
        np.testing.assert_allclose(small_map.u_mm[i, j], sol.r_mm - sol.R_mm, atol=1e-5)
        assert cold.h_mm[i, j] == sol.keypoints.h_mm and cold.residual[i, j] == sol.residual
    assert small_map.converged.all() and cold.converged.all()


def test_query_reproduces_grid_points_and_interpolates_off_grid(small_map):
    q = small_map.query(small_map.diameter_mm[1], small_map.fill[2])
    for name in KEYPOINTS:
        assert getattr(q, name)[0] == pytest.approx(getattr(small_map, name)[1, 2], abs=1e-12)
    rng = np.random.default_rng(3)
    d = rng.uniform(40.0, 44.0, 6)
    p = rng.uniform(0.70, 0.74, 6)
    q = small_map.query(d, p, profiles=True)
    for k in range(d.size):
        sol = solve(Patch(d[k], p[k]))
        h = sol.keypoints.h_mm
        assert abs(q.h_mm[k] - h) <= max(0.01 * h, 0.05)
        assert abs(q.r_a_mm[k] - sol.keypoints.r_a_mm) <= max(0.01 * sol.keypoints.r_a_mm, 0.05)
        np.testing.assert_allclose(q.R_mm[k], sol.R_mm, rtol=1e-12)
        assert np.max(np.abs(q.z_mm[k] - sol.z_mm)) < 0.1
        assert np.max(np.abs(q.r_mm[k] - sol.r_mm)) < 0.1


def test_query_is_vectorized_and_broadcasts(small_map):
    q = small_map.query([40.5, 41.5, 42.5], 0.72)
    assert q.h_mm.shape == (3,)
    assert np.all(np.diff(q.h_mm) > 0)           # h grows with d


@pytest.mark.parametrize("d, p, name", [(39.0, 0.72, "diameter_mm"), (45.5, 0.72, "diameter_mm"),
                                        (42.0, 0.69, "fill"), (42.0, 0.75, "fill"),
                                        (float("nan"), 0.72, "diameter_mm")])
def test_query_outside_domain_names_the_domain(small_map, d, p, name):
    with pytest.raises(InvalidInputError) as info:
        small_map.query([41.0, d], [0.71, p])
    message = str(info.value)
    assert name in message and "d in [40, 44] mm, fill in [0.7, 0.74]" in message


def test_parallel_build_is_bit_identical_to_serial(small_map):
    par = precompute.build(DEFAULT_MATERIAL, small_map.diameter_mm, small_map.fill, workers=2)
    for name in KEYPOINTS + ("energy", "residual"):
        assert np.array_equal(getattr(par, name), getattr(small_map, name))
    assert np.array_equal(par.u_mm, small_map.u_mm) and np.array_equal(par.z_prof_mm, small_map.z_prof_mm)


def test_save_load_round_trip_and_byte_identical(small_map, tmp_path):
    map_io.save_map(small_map, tmp_path / "a.npz")
    map_io.save_map(small_map, tmp_path / "b.npz")
    assert (tmp_path / "a.npz").read_bytes() == (tmp_path / "b.npz").read_bytes()
    back = map_io.load_map(tmp_path / "a.npz")
    for name in KEYPOINTS + ("energy", "residual", "converged", "flags", "diameter_mm", "fill"):
        assert np.array_equal(getattr(back, name), getattr(small_map, name))
    assert np.max(np.abs(back.z_prof_mm - small_map.z_prof_mm)) <= 0.6e-4
    assert back.material == DEFAULT_MATERIAL and back.material_hash == small_map.material_hash


def test_load_rejects_bad_files(tmp_path):
    (tmp_path / "junk.npz").write_bytes(b"not a zip")
    with pytest.raises(InvalidInputError, match="junk.npz"):
        map_io.load_map(tmp_path / "junk.npz")
    np.savez(tmp_path / "other.npz", x=np.zeros(3))
    with pytest.raises(InvalidInputError, match="not a stitchswitch-design-map-1 file"):
        map_io.load_map(tmp_path / "other.npz")


def test_smoothness_violation_detects_an_isolated_outlier():
    d, p = np.meshgrid(np.arange(10.0), np.arange(8.0), indexing="ij")
    h = 5.0 + 0.3 * d + 0.2 * p                 # a plane: smooth
    assert not map_check.violations(h).any()
    h[4, 3] += 0.5
    bad = map_check.violations(h)
    assert bad[4, 3] and bad.sum() == 1         # only the outlier: its neighbours move by 0.125 mm < 2 %


def test_onset_is_explained(small_map):
    """A stencil that holds flat and popped designs is explained as the buckling onset."""
    m = precompute.build(DEFAULT_MATERIAL, np.arange(16.0, 20.0), np.round(np.arange(0.67, 0.755, 0.01), 2))
    flagged = m.flags != FLAG_SMOOTH
    assert flagged.any() and np.any(m.flags == FLAG_ONSET)
    assert set(np.unique(m.flags)) <= {FLAG_SMOOTH, FLAG_ONSET, FLAG_UNRESOLVED}    # none unexplained


def test_parse_range():
    assert precompute.parse_range("15:100:1", "d").size == 86
    assert precompute.parse_range("0.5:1.0:0.01", "p").size == 51
    assert precompute.parse_range("0.5:1.0:0.01", "p")[-1] == 1.0
    for bad in ("1:2", "a:b:c", "5:1:1", "1:5:0", "1:5:-1"):
        with pytest.raises(InvalidInputError, match="STEP"):
            precompute.parse_range(bad, "d")
