"""The candidate effects: their terms are ``Term``s, grid changes keep the derivatives exact, zero
strength is the starting model bit for bit, continuity at zero, each effect changes the
keypoints, and the registry. The added terms' own derivatives are tested in
tests/test_energy_terms.py."""
import dataclasses

import numpy as np
import pytest

from stitchswitch.errors import InvalidInputError
from stitchswitch.reduced.model import assembly
from stitchswitch.reduced.model.discretization import make_grid
from stitchswitch.reduced.model.params import DEFAULT_MATERIAL, Patch
from stitchswitch.reduced.model.terms import ALL_TERMS, Term
from stitchswitch.reduced.solvers.solve import solve
from stitchswitch.validation.discovery.effects import (
    CONTROLS,
    LIBRARY,
    Effect,
    EffectParameter,
    configure,
    get_effect,
    register_effect,
    resolve,
    solve_effects,
)
from stitchswitch.validation.discovery.effects.registry import LIBRARY as REGISTRY

from helpers import fd_gradient as _fd_gradient
from helpers import fd_jacobian, random_state
from helpers import pack as _pack

FAST = DEFAULT_MATERIAL.replace(n_nodes=120, dr_max_mm=1.0)
PATCH = Patch(20.0, 0.8)


def _kp(sol):
    k = sol.keypoints
    return np.array([k.h_mm, k.r_a_mm, k.z_a_mm, k.r_b_mm, k.z_b_mm])


@pytest.mark.parametrize("name", ["fill_exponent", "boundary_transition"])
def test_grid_effects_derivatives_through_wrapped_terms(small_grid, name):
    """Grid changes reach every term; the total derivatives stay exact."""
    material = DEFAULT_MATERIAL.replace(n_nodes=40, w_log=0.5, gamma_mm=1.0)
    effect = get_effect(name)
    _, terms = configure(PATCH, material, {name: (effect.parameters[0].probe * 4,)})
    r, z = random_state(small_grid, 4)
    x = _pack(r, z)
    _, g, hb = assembly.derivatives(r, z, small_grid, terms)
    g_fd = _fd_gradient(lambda y: assembly.energy(y[0::2], y[1::2], small_grid, terms), x)
    np.testing.assert_allclose(g, g_fd, rtol=0, atol=1e-6 * np.max(np.abs(g)))
    H_fd = fd_jacobian(lambda y: assembly.gradient(y[0::2], y[1::2], small_grid, terms), x)
    np.testing.assert_allclose(assembly.band_to_dense(hb), H_fd, rtol=0,
                               atol=1e-6 * np.max(np.abs(H_fd)))


@pytest.mark.parametrize("name", [n for n in (*LIBRARY, *CONTROLS) if resolve(n).terms is not None])
def test_every_effect_term_is_a_term(name):
    """Effects add ``Term`` objects (their kernels and finite-difference tests live in
    ``reduced.model.terms``, tests/test_energy_terms.py); grid changes keep them ``Term``s."""
    effect = resolve(name)
    probe = tuple(p.probe for p in effect.parameters)
    extra = effect.terms(PATCH, DEFAULT_MATERIAL, probe)
    assert extra and all(isinstance(t, Term) for t in extra)
    _, terms = configure(PATCH, DEFAULT_MATERIAL, {name: probe, "fill_exponent": (0.5,)})
    assert len(terms) == len(ALL_TERMS) + len(extra) and all(isinstance(t, Term) for t in terms)


@pytest.mark.parametrize("name", list(LIBRARY))
def test_zero_strength_is_the_starting_model_bit_for_bit(name):
    effect = get_effect(name)
    zero = (0.0,) * len(effect.parameters)
    material, terms = configure(PATCH, FAST, {name: zero})
    assert material is FAST and terms is None
    base = solve(PATCH, FAST)
    sol = solve_effects(PATCH, FAST, {name: zero})
    assert np.array_equal(sol.r_mm, base.r_mm) and np.array_equal(sol.z_mm, base.z_mm)


@pytest.mark.parametrize("name", list(LIBRARY))
def test_tiny_strength_is_continuous_and_probe_changes_keypoints(name):
    """1e-9 of the probe stays within 1e-6 mm of the starting model; 4 probes move h or r_a."""
    effect = get_effect(name)
    patch = Patch(40.0, 0.8)
    base = _kp(solve(patch, FAST))
    tiny = tuple(1e-9 * p.probe for p in effect.parameters)
    kp_tiny = _kp(solve_effects(patch, FAST, {name: tiny}))
    np.testing.assert_allclose(kp_tiny, base, atol=1e-6)
    big = tuple(4 * p.probe for p in effect.parameters)
    sol = solve_effects(patch, FAST, {name: big})
    assert sol.converged
    kp = _kp(sol)
    assert max(abs(kp[0] - base[0]), abs(kp[1] - base[1])) > 0.05


def test_grid_effects_leave_the_fabric_and_p1_alone():
    grid = make_grid(Patch(40.0, 1.0), FAST)
    g2 = get_effect("fill_exponent").grid(grid, Patch(40.0, 1.0), FAST, (1.0,))
    np.testing.assert_array_equal(g2.lam, grid.lam)          # p = 1: p^delta = 1
    grid = make_grid(Patch(40.0, 0.7), FAST)
    g2 = get_effect("fill_exponent").grid(grid, Patch(40.0, 0.7), FAST, (1.0,))
    assert g2.lam[0] == pytest.approx(1 + 0.7 * 0.7 ** 3)
    np.testing.assert_array_equal(g2.lam[grid.n_inside:], 1.0)
    g3 = get_effect("boundary_transition").grid(grid, Patch(40.0, 0.7), FAST, (4.0,))
    assert g3.lam[0] == grid.lam[0] and g3.lam[-1] == 1.0
    assert np.all(np.diff(g3.lam) <= 0)
    # the ramp is centred: the embroidered excess is conserved
    assert np.sum(g3.lam - 1) == pytest.approx(np.sum(grid.lam - 1), rel=1e-12)
    m = get_effect("prestretch_loss").material(FAST, (0.5,))
    assert m.eta == pytest.approx(1.35)


def test_registry_rejects_bad_effects_and_names():
    assert get_effect("hardening") is LIBRARY["hardening"]
    with pytest.raises(InvalidInputError, match="'gravity' is not in the library"):
        get_effect("gravity")
    assert "gravity_sag" not in REGISTRY
    with pytest.raises(InvalidInputError, match="already registered"):
        register_effect(Effect("hardening", "x", "x", (EffectParameter("a", "1", 0, 1, 0.1, (0.1, 0.2)),),
                               material=lambda m, v: m))
    with pytest.raises(InvalidInputError, match="one or two parameters"):
        Effect("x", "x", "x", (), material=lambda m, v: m)
    with pytest.raises(InvalidInputError, match="changes nothing"):
        Effect("x", "x", "x", (EffectParameter("a", "1", 0, 1, 0.1, (0.1, 0.2)),))
    with pytest.raises(InvalidInputError, match="outside"):
        get_effect("hoop_bending").values((-1.0,))
    with pytest.raises(InvalidInputError, match="unknown parameter"):
        get_effect("hoop_bending").values({"nu": 0.3})


def test_registering_a_new_effect_takes_a_few_lines():
    """The documented recipe (docs/discovery.md): an effect that softens the fabric's hoop
    stiffness, as a material change, registered and then solvable by name."""
    effect = Effect(
        name="test_soft_hoop", summary="softer k_theta_fab", physics="k_theta_fab (1 - s)",
        parameters=(EffectParameter("s", "1", 0.0, 0.9, probe=0.1, hidden=(0.3, 0.5)),),
        material=lambda m, v: m.replace(k_theta_fab=m.k_theta_fab * (1 - v[0])))
    register_effect(effect)
    try:
        sol = solve_effects(Patch(40.0, 0.8), FAST, {"test_soft_hoop": (0.5,)})
        assert sol.material.k_theta_fab == pytest.approx(0.25)
    finally:
        REGISTRY.pop("test_soft_hoop")


def test_a_grid_effect_is_applied_once_per_grid_and_changes_no_number(monkeypatch):
    """Every term of a configured model takes its coefficients from one transformed grid
    (the transform runs once per grid, not once per term); a new grid is transformed anew."""
    from stitchswitch.validation.discovery.effects import model as effects_model

    effect = get_effect("fill_exponent")
    material, terms = configure(PATCH, FAST, {"fill_exponent": (0.7,)})
    grid, other = make_grid(PATCH, material), make_grid(Patch(30.0, 0.8), material)
    expected = [[t.coefficients(g) for t in terms] for g in (grid, other)]
    calls = []

    def counted(g, patch, material, values):
        calls.append(g)
        return effect.grid(g, patch, material, values)

    monkeypatch.setattr(effects_model, "resolve",
                        lambda name: dataclasses.replace(effect, grid=counted))
    _, counted_terms = configure(PATCH, FAST, {"fill_exponent": (0.7,)})
    got = [[t.coefficients(grid) for t in counted_terms]]
    assert len(calls) == 1 and len(counted_terms) > 1
    got.append([t.coefficients(other) for t in counted_terms])
    assert len(calls) == 2 and calls[1] is other
    for a, b in zip(got, expected):
        for coef_a, coef_b in zip(a, b):
            for x, y in zip(coef_a, coef_b):
                np.testing.assert_array_equal(x, y)
