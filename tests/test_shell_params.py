"""The shell's own parameters: validation, the parameter map from Material, the switches,
and the optional loads (thickness-based bending, gravity)."""
import numpy as np
import pytest

from stitchswitch.errors import InvalidInputError
from stitchswitch.fem_reference.revolution import SWITCHES, ShellParams, equilibrium
from stitchswitch.fem_reference.revolution.moduli import region_moduli
from stitchswitch.reduced.model.params import DEFAULT_MATERIAL, Patch


@pytest.mark.parametrize("field, value", [("nu", 0.6), ("kappa0_per_mm", 2.0), ("elements_inside", 2),
                                          ("thickness_mm", 0.0), ("hoop_bending", 1),
                                          ("areal_weight_n_per_m2", -1.0), ("nu", float("nan"))])
def test_bad_parameters_are_refused_by_name(field, value):
    with pytest.raises(InvalidInputError, match=field):
        ShellParams(**{field: value})


def test_switches_turn_off_one_physics_each():
    p = ShellParams(kappa0_per_mm=0.05)
    assert not p.without("hoop_bending").hoop_bending and p.without("poisson").nu == 0.0
    assert not p.without("relaxed_membrane").relaxed_membrane
    assert p.without("natural_curvature").kappa0_per_mm == 0.0
    base = p.reduced_like()
    assert all(base.without(s) == base for s in SWITCHES)
    with pytest.raises(InvalidInputError):
        p.without("gravity")


def test_parameter_map_from_the_material():
    patch = Patch(60.0, 0.8)
    inner, outer = region_moduli(patch, DEFAULT_MATERIAL, ShellParams())
    m = DEFAULT_MATERIAL
    p2 = 0.64
    lam = 1 + (m.eta - 1) * p2
    assert inner.lam == pytest.approx(lam) and outer.lam == 1.0
    assert inner.a_s == pytest.approx(2 * (m.k_r_emb * p2 + m.k_r_fab * (1 - p2)) * lam)
    assert outer.a_t == pytest.approx(2 * m.k_theta_fab)
    assert outer.bending == pytest.approx(m.w_b_fab * 0.25 / 4)
    assert outer.relaxed and not inner.relaxed and outer.kappa0_per_mm == 0.0
    thick, _ = region_moduli(patch, m, ShellParams(thickness_mm=0.8))
    assert thick.bending == pytest.approx(np.sqrt(inner.a_s * inner.a_t) * 0.64 / 12)


def test_gravity_lowers_the_dome():
    patch = Patch(90.0, 0.8)
    up = equilibrium(patch).apex_mm
    heavy = equilibrium(patch, params=ShellParams(areal_weight_n_per_m2=5.0, knit_stiffness_n_per_m=50.0))
    assert heavy.certified and heavy.apex_mm < up - 0.01
