"""The fused compiled energy (``solvers.fused``) against the Python assembly of the same terms,
the compiled Newton loop against the interpreted one, the coefficients' conversion against
numpy's general rule, and one prepared energy (``newton.prepare``) serving several starts."""
import dataclasses

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from hypothesis.extra import numpy as hnp

from stitchswitch import DEFAULT_MATERIAL, Patch
from stitchswitch.reduced.model import assembly
from stitchswitch.reduced.model.discretization import make_grid
from stitchswitch.reduced.model.terms import ALL_TERMS, hardening, variants
from stitchswitch.reduced.model.terms.extra import gravity, hoop_bending, natural_curvature
from stitchswitch.reduced.solvers import continuation, fused, newton
from stitchswitch.reduced.solvers.solve import DEFAULT_TOL


def _state(grid, seed):
    rng = np.random.default_rng(seed)
    r, z = continuation.released_state(grid)
    r = r * (1.0 + 0.02 * rng.standard_normal(r.size))
    r[0] = 0.0
    z = np.sort(z + rng.uniform(0.0, 0.5, z.size))[::-1].copy()
    return r, z - z[-1]


@pytest.mark.parametrize("terms", [ALL_TERMS, variants.HOOP_NODE_AVERAGE_TERMS, variants.PAPER_INDEXING],
                         ids=["default", "hoop_node_average", "paper_indexing"])
@pytest.mark.parametrize("design", [(15.0, 0.6), (40.0, 0.8), (100.0, 1.0)])
def test_fused_derivatives_equal_the_python_assembly(terms, design):
    grid = make_grid(Patch(*design), DEFAULT_MATERIAL)
    coef = fused.coefficients(terms, grid)
    assert coef is not None
    model = assembly.Model(grid, terms)
    for seed in range(3):
        r, z = _state(grid, seed)
        E, g, hb = model.derivatives(r, z)
        grad, band = np.zeros_like(g), np.zeros_like(hb)
        E_f = fused.derivatives(r, z, coef, grad, band, True)
        np.testing.assert_allclose(E_f, E, rtol=1e-14)
        np.testing.assert_allclose(grad, g, rtol=1e-13, atol=1e-15)
        np.testing.assert_allclose(band, hb, rtol=1e-13, atol=1e-15)
        np.testing.assert_allclose(fused.energy(r, z, coef), model.energy(r, z), rtol=1e-14)


def _assert_same_bits(model, coef, r, z):
    """The fused energy, gradient and Hessian at (r, z) are ``model``'s bit for bit."""
    E, g, hb = model.derivatives(r, z)
    grad, band = np.zeros_like(g), np.zeros_like(hb)
    assert fused.derivatives(r, z, coef, grad, band, True) == E
    assert grad.tobytes() == g.tobytes() and band.tobytes() == hb.tobytes()
    assert fused.energy(r, z, coef) == model.energy(r, z)


def _other_rest_length(term, factor):
    """``term`` with its rest lengths scaled (its kernel kept: still the fused path)."""
    def coefficients(grid):
        lam, *rest = term.coefficients(grid)
        return (lam * factor, *rest)
    return dataclasses.replace(term, coefficients=coefficients)


@pytest.mark.parametrize("compression_lam", [1.0, 0.97], ids=["one_rest_length", "two"])
@pytest.mark.parametrize("design", [(15.0, 0.6), (55.0, 1.0)])
def test_fused_numbers_are_the_term_kernels_bit_for_bit(design, compression_lam):
    """The fused loops (one segment loop for the radial and compressive terms) change no
    rounding: energy, gradient and Hessian equal the term-by-term assembly exactly, on states
    with stretched, slack and level segments, and with the two terms' rest lengths apart
    (where the fused path runs the kernels one after the other)."""
    terms = list(ALL_TERMS)
    if compression_lam != 1.0:
        terms[1] = _other_rest_length(terms[1], compression_lam)
    grid = make_grid(Patch(*design), DEFAULT_MATERIAL)
    coef = fused.coefficients(terms, grid)
    assert coef is not None
    model = assembly.Model(grid, terms)
    for seed in range(4):
        r, z = _state(grid, seed)
        k = grid.n_inside + 5                      # a level stretch, as held drops give
        z[k:], r[k:] = 0.0, grid.R[k:] * 1.01
        _assert_same_bits(model, coef, r, z)


def test_fused_energy_is_infinite_outside_the_domain():
    grid = make_grid(Patch(40.0, 0.8), DEFAULT_MATERIAL)
    coef = fused.coefficients(ALL_TERMS, grid)
    r, z = continuation.released_state(grid)
    r[5] = -1.0
    assert fused.energy(r, z, coef) == np.inf == assembly.Model(grid).energy(r, z)
    r[5] = np.nan
    assert fused.energy(r, z, coef) == np.inf


EXTRA_TERMS = {
    "hardening": hardening.with_weight(2.0, 5.0),
    "natural_curvature": natural_curvature.term(0.08, 0.8),
    "hoop_bending": hoop_bending.term(2.5),
    "gravity": gravity.term(0.3, 0.8, 2.0),
}


@pytest.mark.parametrize("extra", [("hardening",), ("natural_curvature",), ("hoop_bending",),
                                   ("gravity",), ("hardening", "natural_curvature", "hoop_bending", "gravity")],
                         ids=lambda e: "+".join(e))
@pytest.mark.parametrize("design", [(15.0, 0.6), (55.0, 1.0)])
def test_fused_added_terms_are_the_term_kernels_bit_for_bit(extra, design):
    """The terms the discovery effects add (a second hardening, natural curvature, hoop
    bending, gravity) run in the compiled energy too, after the default terms and in the
    assembly's order: the same energy, gradient and Hessian bit for bit."""
    terms = ALL_TERMS + tuple(EXTRA_TERMS[name] for name in extra)
    grid = make_grid(Patch(*design), DEFAULT_MATERIAL)
    coef = fused.coefficients(terms, grid)
    assert coef is not None
    model = assembly.Model(grid, terms)
    for seed in range(3):
        r, z = _state(grid, seed)
        _assert_same_bits(model, coef, r, z)
    # and the added terms change the numbers: they are evaluated, not dropped
    base = fused.coefficients(ALL_TERMS, grid)
    assert fused.energy(r, z, base) != fused.energy(r, z, coef)


def test_other_term_tuples_take_the_python_path():
    grid = make_grid(Patch(40.0, 0.8), DEFAULT_MATERIAL)
    assert fused.coefficients(ALL_TERMS[::-1], grid) is None
    assert fused.coefficients(ALL_TERMS[:-1], grid) is None
    g, h = EXTRA_TERMS["gravity"], EXTRA_TERMS["hoop_bending"]
    assert fused.coefficients(ALL_TERMS + (g, h), grid) is None          # not in EXTRAS order
    assert fused.coefficients(ALL_TERMS + (g, g), grid) is None          # a kind twice
    wrapped = dataclasses.replace(g, energy=lambda r, z, c: g.energy(r, z, c))
    assert fused.coefficients(ALL_TERMS + (wrapped,), grid) is None      # another kernel


def _interpreted_terms():
    """The default terms with the bending kernel wrapped in a Python function: the same energy,
    which ``fused.coefficients`` does not recognize, so the solver runs it interpreted."""
    bending = ALL_TERMS[-1]
    wrapped = dataclasses.replace(bending, accumulate=lambda r, z, c, g, h: bending.accumulate(r, z, c, g, h))
    return ALL_TERMS[:-1] + (wrapped,)


@pytest.mark.parametrize("design", [(25.0, 1.0), (70.0, 0.6)])
def test_compiled_and_interpreted_newton_reach_the_same_certified_state(design):
    grid = make_grid(Patch(*design), DEFAULT_MATERIAL)
    r0, z0 = continuation.released_state(grid)
    interpreted_terms = _interpreted_terms()
    assert fused.coefficients(interpreted_terms, grid) is None
    a = newton.minimize(grid, r0, z0, tol=DEFAULT_TOL, max_iter=300)
    b = newton.minimize(grid, r0, z0, tol=DEFAULT_TOL, max_iter=300, terms=interpreted_terms)
    assert a.converged and b.converged and a.second_order and b.second_order
    np.testing.assert_allclose(a.energy, b.energy, rtol=1e-12)
    np.testing.assert_allclose(a.z, b.z, atol=1e-6)
    np.testing.assert_allclose(a.r, b.r, atol=1e-6)
    again = newton.minimize(grid, r0, z0, tol=DEFAULT_TOL, max_iter=300)
    assert np.array_equal(again.z, a.z) and again.iterations == a.iterations     # deterministic


_VALUES = st.one_of(
    st.floats(allow_nan=False), st.integers(-5, 5),
    st.builds(np.float64, st.floats(allow_nan=False)),
    hnp.arrays(st.sampled_from([np.float64, np.float32, np.int64]),
               hnp.array_shapes(min_dims=0, max_dims=2, max_side=3)),
    hnp.arrays(np.float64, (6,)).map(lambda a: a[::2]),          # not contiguous
    st.lists(st.floats(allow_nan=False), max_size=3))


@given(value=_VALUES, ndim=st.sampled_from(["index", -1, 1, 2]))
def test_prepared_coefficients_follow_the_general_rule(value, ndim):
    """The fast paths of ``_prepared`` give what numpy's conversion gives."""
    got, want = fused._prepared(value, ndim), fused._converted(value, ndim)
    assert (got is None) == (want is None)
    if want is not None:
        assert type(got) is type(want)
        np.testing.assert_array_equal(got, want)
        assert np.asarray(got).dtype == np.asarray(want).dtype


@pytest.mark.parametrize("terms", [None, _interpreted_terms()], ids=["fused", "interpreted"])
def test_a_prepared_energy_serves_several_starts_with_the_same_result(terms):
    grid = make_grid(Patch(40.0, 0.8), DEFAULT_MATERIAL)
    prepared = newton.prepare(grid, terms)
    for fraction in (continuation.SEED_FRACTION, continuation.RETRY_SEED_FRACTION):
        r0, z0 = continuation.released_state(grid, fraction)
        a = newton.minimize(grid, r0, z0, tol=DEFAULT_TOL, max_iter=300, terms=terms)
        b = newton.minimize(grid, r0, z0, tol=DEFAULT_TOL, max_iter=300, prepared=prepared)
        assert a.converged and a.iterations == b.iterations and a.energy == b.energy
        assert np.array_equal(a.r, b.r) and np.array_equal(a.z, b.z)
