"""The shipped default material is the paper-magnitude fit (``reduced.calibration.magnitudes``,
scripts/fit_default_material.py): its mean keypoints over the 25 calibration designs are within
15 % of those Table 1 implies, it shows the paper's qualitative findings, its file says what it
is, and no equilibrium on the shipped design map reaches the hardening term's continuation."""
import numpy as np
import pytest

from stitchswitch import DEFAULT_MATERIAL, Patch, solve
from stitchswitch.reduced.calibration import magnitudes
from stitchswitch.reduced.design_space.cache import default_map
from stitchswitch.reduced.model.discretization import make_grid
from stitchswitch.reduced.model.material_io import default_material_path, material_from_json
from stitchswitch.reduced.model.terms.hardening import CUTOFF, limit_ratio


@pytest.fixture(scope="module")
def evaluation():
    return magnitudes.evaluate(DEFAULT_MATERIAL)


def test_table1_means_are_the_ratio_of_mae_and_percentage_error():
    assert magnitudes.TABLE1_MEANS_MM["h_mm"] == pytest.approx(1.44 / 0.147)
    assert [round(v, 1) for v in magnitudes.TABLE1_MEANS_MM.values()] == [9.8, 19.3, 5.3, 17.2, 4.1]


@pytest.mark.parametrize("key", magnitudes.KEYS)
def test_mean_keypoint_within_15_percent_of_table1(evaluation, key):
    want = magnitudes.TABLE1_MEANS_MM[key]
    assert evaluation.means_mm[key] == pytest.approx(want, rel=0.15)


def test_every_probe_certifies_and_stays_below_the_hardening_margin(evaluation):
    assert evaluation.uncertified == 0
    assert evaluation.limit_ratio <= magnitudes.HARDENING_MARGIN


def test_qualitative_findings():
    def kp(d, p):
        return solve(Patch(d, p)).keypoints

    assert kp(15.0, 0.6).h_mm < 1.0                                   # small, sparse: near flat
    assert kp(20.0, 0.5).h_mm < 1.0
    heights = [kp(d, 0.8).h_mm for d in (20.0, 40.0, 60.0, 90.0)]
    assert all(a < b for a, b in zip(heights, heights[1:]))          # h grows with d
    big = kp(90.0, 1.0)
    assert big.b_rule == "neck" and big.r_a_mm - big.r_b_mm > 0.5     # overhanging mushroom
    assert kp(40.0, 0.6).b_rule != "neck"                             # lower fill: a smooth dome
    # saturation: "increasing density shifts deformation from vertical height to lateral
    # distribution": per unit of boundary displacement, more fill raises the dome much less at
    # high fill than at low fill, once the patch is large enough to saturate
    for d in (60.0, 90.0):
        a, b, c, e = kp(d, 0.5), kp(d, 0.6), kp(d, 0.9), kp(d, 1.0)
        low = (b.h_mm - a.h_mm) / (b.r_a_mm - a.r_a_mm)
        high = (e.h_mm - c.h_mm) / (e.r_a_mm - c.r_a_mm)
        assert 0.0 < high < 0.25 * low, (d, low, high)


def test_the_file_is_the_material_and_says_what_it_is():
    shipped = material_from_json(default_material_path().read_text(encoding="utf-8"))
    assert shipped == DEFAULT_MATERIAL
    assert "paper-magnitude" in shipped.label and "NOT fitted to fabricated samples" in shipped.label


def test_no_equilibrium_on_the_shipped_map_reaches_the_hardening_continuation():
    """The map's profiles are the certified equilibria of the default material: the largest
    eps_theta / gamma over all 4386 designs stays below the continuation's start 1 - CUTOFF."""
    dmap = default_map()
    assert dmap.material == DEFAULT_MATERIAL
    worst = 0.0
    for i, d in enumerate(dmap.diameter_mm):
        for j, p in enumerate(dmap.fill):
            grid = make_grid(Patch(float(d), float(p)), dmap.material)
            r = grid.R + dmap.u_mm[i, j].astype(float) / grid.dr_mm
            worst = max(worst, limit_ratio(grid, r))
    assert worst < 1.0 - CUTOFF
    assert np.isfinite(worst) and worst > 0.1                         # the term is active
