"""Calibration by differential evolution: recovery of known parameters, identifiability."""
import numpy as np
import pytest

from stitchswitch import DEFAULT_MATERIAL, InvalidInputError
from stitchswitch.reduced.calibration import evolution as cal
from stitchswitch.reduced.model.params import Patch
from stitchswitch.reduced.solvers.solve import solve

TRUE = DEFAULT_MATERIAL.replace(w_b_emb=14.0, k_r_emb=1.6)
DESIGNS = [(30.0, 0.7), (30.0, 0.9), (50.0, 0.7), (50.0, 0.9), (80.0, 0.8)]


@pytest.fixture(scope="module")
def recovered():
    measured, bad = cal.predict_keypoints(TRUE, DESIGNS)
    assert bad == 0
    result = cal.calibrate(DESIGNS, measured, DEFAULT_MATERIAL, maxiter=12, popsize=6, seed=3,
                           free=("w_b_emb", "k_r_emb"))
    return result, measured


def test_recovers_keypoints_of_noise_free_synthetic_data(recovered):
    result, measured = recovered
    pred, bad = cal.predict_keypoints(result.material, DESIGNS)
    assert bad == 0
    assert np.max(np.abs(pred - measured) / np.abs(measured)) < 0.01          # within 1 %
    assert result.material.w_b_emb == pytest.approx(14.0, rel=0.05)
    assert result.material.k_r_emb == pytest.approx(1.6, rel=0.05)
    start_pred, _ = cal.predict_keypoints(DEFAULT_MATERIAL, DESIGNS)
    assert result.mse_mm2 < 0.01 * np.mean((start_pred - measured) ** 2)


def test_spreads_record_the_termination_measure(recovered):
    """One spread per generation, the measure scipy's termination compares with ``tol``: the
    search stops at the first generation whose spread is at most ``tol``, or at ``maxiter``."""
    result, _ = recovered
    spreads = np.array(result.spreads)
    assert len(spreads) == result.generations > 0 and np.all(spreads >= 0)
    assert np.all(spreads[:-1] > cal.DE_TOL)
    assert spreads[-1] <= cal.DE_TOL or result.generations == 12
    assert cal.population_spread([1.0, 3.0]) == pytest.approx(0.5)


def test_identifiability_report(recovered):
    result, _ = recovered
    ident = result.identifiability
    assert "overall scale" in ident["not_identifiable"] and cal.SCALE_PARAM in ident["not_identifiable"]
    assert len(ident["singular_values"]) == 2 and ident["condition_number"] >= 1.0


def test_overall_scale_is_not_identifiable():
    """Scaling every coefficient by one factor leaves the equilibrium unchanged."""
    scaled = DEFAULT_MATERIAL.replace(**{n: 3.0 * getattr(DEFAULT_MATERIAL, n) for n in cal.COEFFICIENTS})
    a, b = solve(Patch(45.0, 0.8)), solve(Patch(45.0, 0.8), scaled)
    np.testing.assert_allclose(a.z_mm, b.z_mm, atol=1e-6)      # solver tolerance
    assert b.energy == pytest.approx(3.0 * a.energy, rel=1e-9)


def test_identifiability_flags_a_redundant_pair():
    """The same parameter listed twice is a redundant pair: one singular value vanishes and
    the weak direction is reported."""
    measured, _ = cal.predict_keypoints(DEFAULT_MATERIAL, DESIGNS[:3])
    obj = cal.Objective(DEFAULT_MATERIAL, ("k_r_emb", "k_r_emb"), tuple(DESIGNS[:3]), measured)
    ident = cal.identifiability(obj, cal._to_x(DEFAULT_MATERIAL.as_dict(), obj.free))
    assert ident["singular_values"][1] < 1e-6 * ident["singular_values"][0]
    assert len(ident["weak_directions"]) == 1


def test_parallel_evaluation_matches_serial():
    """The search's members, the polish's and the identifiability report's designs evaluated
    on two processes give the serial run's numbers exactly."""
    from stitchswitch.executor import make_executor

    measured, _ = cal.predict_keypoints(TRUE, DESIGNS[:3])
    kwargs = dict(maxiter=2, popsize=4, seed=5, free=("w_b_emb",))
    serial = cal.calibrate(DESIGNS[:3], measured, DEFAULT_MATERIAL, **kwargs)
    with make_executor(2) as ex:
        par = cal.calibrate(DESIGNS[:3], measured, DEFAULT_MATERIAL, executor=ex, **kwargs)
        kp, bad = cal.predict_keypoints(TRUE, DESIGNS[:3], executor=ex)
    assert "polished" in serial.message and par.message == serial.message
    assert par.material == serial.material and par.mse_mm2 == serial.mse_mm2
    assert par.identifiability == serial.identifiability
    assert bad == 0 and np.array_equal(kp, measured)


def test_bad_arguments():
    with pytest.raises(InvalidInputError, match="k_theta_fab"):
        cal.calibrate(DESIGNS, np.zeros((5, 5)), DEFAULT_MATERIAL, free=("k_theta_fab",))
    with pytest.raises(InvalidInputError, match="measured"):
        cal.calibrate(DESIGNS, np.zeros((4, 5)), DEFAULT_MATERIAL)


def test_synthetic_dataset_is_reproducible_and_labelled(tmp_path):
    import importlib.util
    import pathlib

    root = pathlib.Path(__file__).resolve().parent.parent
    spec = importlib.util.spec_from_file_location("gen", root / "scripts" / "make_measured_dataset.py")
    gen = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(gen)
    gen.main([str(tmp_path / "m.csv")])
    shipped = root / "src" / "stitchswitch" / "data" / "measured_synthetic.csv"
    assert (tmp_path / "m.csv").read_bytes() == shipped.read_bytes()
    first = shipped.read_text().splitlines()[0]
    assert first.startswith("# source: synthetic") and "NOT measured" in first
    from stitchswitch.validation.measured import load_measurements
    data = load_measurements(shipped)
    assert len(data.split("train")) == 25 and len(data.split("val")) == 28 and data.synthetic


@pytest.mark.slow
def test_recovers_the_full_parameter_set_from_noise_free_data():
    """Every default-free parameter (the coefficients but the scale, c_emb, c_fab, jam, c_jam
    and gamma_mm) fitted at once to the noise-free keypoints of the reference dataset's true
    material on eight of its training designs: differential evolution and the polish bring
    every keypoint within 1 %."""
    designs = [(20.0, 0.8), (40.0, 0.6), (40.0, 1.0), (60.0, 0.7), (60.0, 0.9), (70.0, 0.8),
               (90.0, 0.6), (90.0, 1.0)]
    from stitchswitch.validation.reference_truth import true_material

    true = true_material()
    measured, bad = cal.predict_keypoints(true, designs)
    assert bad == 0
    result = cal.calibrate(designs, measured, DEFAULT_MATERIAL, maxiter=6, popsize=4, seed=1,
                           check_identifiability=False)
    assert result.free == cal.DEFAULT_FREE and len(result.free) == 11
    assert "polished" in result.message
    pred, bad = cal.predict_keypoints(result.material, designs)
    assert bad == 0
    assert np.max(np.abs(pred - measured) / np.maximum(np.abs(measured), 1.0)) < 0.01


def test_search_resolution_keeps_the_domain_and_the_result_is_the_fine_models():
    """The search runs on fewer nodes over the same domain (every design's outer radius stays
    put), and what ``calibrate`` reports (material, MSE) is the start's own resolution's."""
    from stitchswitch.reduced.model.discretization import make_grid

    coarse = cal.search_material(DEFAULT_MATERIAL)
    assert coarse.n_nodes == cal.SEARCH_NODES < DEFAULT_MATERIAL.n_nodes
    for d, p in DESIGNS + [(15.0, 0.6), (100.0, 1.0)]:
        fine_grid, coarse_grid = make_grid(Patch(d, p), DEFAULT_MATERIAL), make_grid(Patch(d, p), coarse)
        outer = [(g.n_nodes - 1) * g.dr_mm for g in (fine_grid, coarse_grid)]
        assert outer[1] == pytest.approx(outer[0], rel=0.02)
    assert cal.search_material(DEFAULT_MATERIAL, None) is DEFAULT_MATERIAL
    measured, _ = cal.predict_keypoints(TRUE, DESIGNS[:3])
    result = cal.calibrate(DESIGNS[:3], measured, DEFAULT_MATERIAL, maxiter=2, popsize=3, seed=0,
                           free=("w_b_emb",), check_identifiability=False)
    assert result.material.n_nodes == DEFAULT_MATERIAL.n_nodes
    pred, _ = cal.predict_keypoints(result.material, DESIGNS[:3])
    assert result.mse_mm2 == pytest.approx(float(np.mean((pred - measured) ** 2)), rel=1e-12)
