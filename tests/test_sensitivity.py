"""The sensitivity table (reduced.calibration.sensitivity): exactly known derivatives, the
homogeneity of the energy, the flags, determinism and parallel = serial."""
import json
import math

import pytest

from stitchswitch.errors import InvalidInputError
from stitchswitch.files.jsonsafe import json_safe
from stitchswitch.reduced.calibration import sensitivity as sens
from stitchswitch.reduced.calibration.evolution import COEFFICIENTS, PARAMS
from stitchswitch.reduced.model.params import DEFAULT_MATERIAL

TAUT = (70.0, 1.0)      # every segment taut: docs/model.md, compression as physics
SLACK = (40.0, 0.8)     # segments go slack: h depends on the compressive response


def _get(result, design, parameter, keypoint):
    return next(x for x in result.derivatives
                if ((x.diameter_mm, x.fill), x.parameter, x.keypoint) == (design, parameter, keypoint))


def test_parameters_are_the_physical_float_fields():
    assert sens.parameter_names() == COEFFICIENTS + ("c_emb", "c_fab", "jam", "c_jam", "gamma_mm", "eta")
    assert set(PARAMS) < set(sens.parameter_names())
    everything = sens.parameter_names(include_numerical=True)
    assert set(everything) - set(sens.parameter_names()) == set(sens.NUMERICAL)
    assert "n_nodes" not in everything


def test_the_jamming_stretch_does_not_enter_a_taut_design_but_a_slack_one():
    result = sens.sensitivity(DEFAULT_MATERIAL, [TAUT, SLACK], parameters=["jam"])
    for q in sens.KEYPOINTS:
        taut = _get(result, TAUT, "jam", q)
        assert taut.flag == "" and abs(taut.dq_dlog_mm) < 1e-9 and abs(taut.elasticity) < 1e-9
    slack = _get(result, SLACK, "jam", "h_mm")
    assert slack.flag == "" and slack.elasticity > 0.1       # later jamming: a taller dome


def test_h_grows_with_the_pre_stretch_at_a_popped_design():
    x = _get(sens.sensitivity(DEFAULT_MATERIAL, [SLACK], parameters=["eta"]), SLACK, "eta", "h_mm")
    assert x.flag == "" and x.value_mm > 5.0 and x.dq_dlog_mm > 1.0 and x.elasticity > 0.1


def test_scaling_all_seven_coefficients_changes_nothing():
    """The energy is homogeneous of degree one in the seven coefficients, so (Euler) their
    log-derivatives sum to zero for every keypoint; central differences leave O(step^2)."""
    result = sens.sensitivity(DEFAULT_MATERIAL, [SLACK], 0.01, parameters=COEFFICIENTS)
    for q in sens.KEYPOINTS:
        slopes = [_get(result, SLACK, n, q).dq_dlog_mm for n in COEFFICIENTS]
        assert abs(sum(slopes)) < 1e-3 * sum(abs(s) for s in slopes), (q, slopes)


def test_a_kink_is_flagged_and_left_out_of_the_summary():
    """At d = 90 mm, p = 0.7 the overhang begins: h's slope in log eta is about 75 mm below
    eta = 1.7 (h 13.18 -> 16.92 mm, the steepest point becomes a neck) and -0.8 mm above it."""
    design = (90.0, 0.7)
    result = sens.sensitivity(DEFAULT_MATERIAL, [design, SLACK], parameters=["eta"])
    kink = _get(result, design, "eta", "h_mm")
    assert kink.flag == sens.FLAG_NOT_SMOOTH and math.isnan(kink.dq_dlog_mm)
    row = result.row("eta", "h_mm")
    assert (row.n_designs, row.n_flagged) == (2, 1)
    assert row.max_abs_dq_dlog_mm == pytest.approx(abs(_get(result, SLACK, "eta", "h_mm").dq_dlog_mm))


def test_flat_patch_has_no_elasticity_of_h_but_a_slope():
    result = sens.sensitivity(DEFAULT_MATERIAL, [(15.0, 0.5)], parameters=["w_b_emb"])
    x = _get(result, (15.0, 0.5), "w_b_emb", "h_mm")
    assert x.flag == "" and abs(x.value_mm) < 1e-6
    assert math.isnan(x.elasticity) and x.dq_dlog_mm == pytest.approx(0.0, abs=1e-9)
    row = result.row("w_b_emb", "h_mm")
    assert row.n_undefined == 1 and math.isnan(row.median_abs_elasticity)
    assert row.median_abs_dq_dlog_mm == pytest.approx(0.0, abs=1e-9)


def test_a_perturbation_outside_the_valid_range_is_flagged():
    result = sens.sensitivity(DEFAULT_MATERIAL.replace(eta=2.95), [SLACK], parameters=["eta", "w_log"])
    assert {x.flag for x in result.derivatives if x.parameter == "eta"} == {sens.FLAG_OUT_OF_RANGE}
    assert result.row("eta", "h_mm").n_flagged == 1


def test_deterministic_and_parallel_equals_serial():
    designs, params = [TAUT, SLACK, (20.0, 0.6)], ["w_b_emb", "eta"]
    serial = sens.sensitivity(DEFAULT_MATERIAL, designs, parameters=params).as_dict()
    again = sens.sensitivity(DEFAULT_MATERIAL, designs, parameters=params).as_dict()
    parallel = sens.sensitivity(DEFAULT_MATERIAL, designs, parameters=params, workers=2).as_dict()
    assert json.dumps(json_safe(serial)) == json.dumps(json_safe(again)) == json.dumps(json_safe(parallel))
    assert serial["n_solves"] == 3 * (1 + 2 * len(params))
    assert len(serial["rows"]) == len(params) * len(sens.KEYPOINTS)
    json.dumps(json_safe(serial), allow_nan=False)


def test_calibration_designs_are_the_papers_25():
    assert len(sens.CALIBRATION_DESIGNS) == len(set(sens.CALIBRATION_DESIGNS)) == 25
    assert {d for d, _ in sens.CALIBRATION_DESIGNS} == {20.0, 40.0, 60.0, 70.0, 90.0}
    assert {p for _, p in sens.CALIBRATION_DESIGNS} == {0.6, 0.7, 0.8, 0.9, 1.0}


@pytest.mark.parametrize("kwargs, expected", [
    ({"step": 0.0}, "step"), ({"step": 0.9}, "step"), ({"parameters": ["n_nodes"]}, "n_nodes"),
    ({"parameters": ["stiffness"]}, "stiffness"), ({"designs": []}, "designs"),
    ({"designs": [(5.0, 0.8)]}, "diameter_mm"),
])
def test_bad_input_is_invalid_input_error(kwargs, expected):
    with pytest.raises(InvalidInputError, match=expected):
        sens.sensitivity(DEFAULT_MATERIAL, **{"designs": [SLACK], **kwargs})
