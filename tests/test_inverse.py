"""Inverse design: confirmed suggestions, bounds, unreachable targets, the selection program."""
import numpy as np
import pytest

from stitchswitch import InvalidInputError, Patch, solve
from stitchswitch.reduced.design_space.inverse import HEIGHT_TOL_MM, InverseTarget, inverse_design
from stitchswitch.reduced.design_space.inverse_mip import select


def _check_confirmed(c):
    sol = solve(Patch(c.diameter_mm, c.fill))
    assert c.h_mm == pytest.approx(sol.keypoints.h_mm, abs=1e-12)
    assert c.converged and c.residual <= 1e-9


@pytest.mark.parametrize("height", [5.0, 12.0, 17.5, 17.8])
def test_suggestions_meet_the_target_and_are_direct_solves(height):
    result = inverse_design(InverseTarget(height, count=4))
    assert 1 <= len(result.candidates) <= 4
    for c in result.candidates:
        assert abs(c.h_mm - height) <= HEIGHT_TOL_MM
        _check_confirmed(c)
    ds = [c.diameter_mm for c in result.candidates]
    assert len(set(np.round(ds, 1))) == len(ds)                      # distinct alternatives
    assert result.selection.status == "optimal"


def test_bounds_are_respected():
    target = InverseTarget(15.0, max_diameter_mm=60.0, min_fill=0.8, force_range_N=(0.1, 0.4), count=3)
    result = inverse_design(target)
    assert result.candidates
    for c in result.candidates:
        assert c.diameter_mm <= 60.0 and c.fill >= 0.8 - 1e-12 and 0.1 <= c.force_N <= 0.4
        assert abs(c.h_mm - 15.0) <= HEIGHT_TOL_MM


def test_radius_target():
    result = inverse_design(InverseTarget(8.0, radius_mm=15.0, count=3))
    best = result.candidates[0]
    assert abs(best.h_mm - 8.0) <= HEIGHT_TOL_MM and abs(best.r_a_mm - 15.0) <= 0.2
    _check_confirmed(best)


@pytest.mark.parametrize("target, range_text", [
    (InverseTarget(40.0), "h ranges from 0.00 to 17.93 mm"),
    (InverseTarget(20.0, max_diameter_mm=40.0), "d <= 40 mm"),
])
def test_unreachable_target_names_the_achievable_range(target, range_text):
    with pytest.raises(InvalidInputError) as info:
        inverse_design(target)
    assert "not achievable" in str(info.value) and range_text in str(info.value)


@pytest.mark.parametrize("kwargs, name", [({"height_mm": -1.0}, "height_mm"),
                                          ({"height_mm": float("nan")}, "height_mm"),
                                          ({"height_mm": 5.0, "min_fill": 1.5}, "min_fill"),
                                          ({"height_mm": 5.0, "force_range_N": (0.5, 0.1)}, "force_range_N"),
                                          ({"height_mm": 5.0, "count": 0}, "count")])
def test_invalid_targets(kwargs, name):
    with pytest.raises(InvalidInputError, match=name):
        InverseTarget(**kwargs)


def test_selection_program_picks_the_cheapest_per_bin():
    cost = np.array([0.5, 0.1, 0.3, 0.2, 0.9, 0.05])
    d = np.array([10.0, 11.0, 16.0, 17.0, 21.0, 22.0])
    p = np.full(6, 0.8)
    force = np.array([0.1, 0.2, 0.3, 0.4, 0.5, 0.6])
    s = select(cost, d, p, force, count=3, bin_width_mm=5.0, bin_origin_mm=10.0)
    assert list(s.indices) == [5, 1, 3]          # best of each bin, cheapest first
    s = select(cost, d, p, force, count=3, bin_width_mm=5.0, bin_origin_mm=10.0, force_range=(0.0, 0.45))
    assert list(s.indices) == [1, 3]             # the last bin has no design in the window
    s = select(cost, d, p, force, count=2, bin_width_mm=5.0, bin_origin_mm=10.0, d_max=15.0)
    assert list(s.indices) == [1]


def test_force_extrapolation_is_flagged():
    result = inverse_design(InverseTarget(17.5, count=5))
    for c in result.candidates:
        outside = not (20.0 <= c.diameter_mm <= 90.0 and 0.6 <= c.fill <= 1.0)
        assert c.force_extrapolated is outside
