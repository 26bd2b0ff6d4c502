"""The envelope-limited banded factor (``banded.factor_rows``, ``banded.solve_rows``) against
the full-band elimination (the same root-free loops over every entry of the band): the same
numbers bit for bit on bands made wide by long merged z groups, so the envelope skips only
updates by exact zeros and does not change the solver's iterates."""
import numpy as np
import pytest
from numba import njit
from scipy.linalg.lapack import dpbtrf

from stitchswitch.reduced.model.terms.segment import BANDWIDTH
from stitchswitch.reduced.solvers import banded, bordered, step

from helpers import solver_states


@njit(fastmath=banded.CONTRACT)
def _full_band_factor(At, shift):
    """The root-free right-looking elimination over the whole band width (band rows, compiled
    with the same floating-point contraction)."""
    n, kd = At.shape[0], At.shape[1] - 1
    F = At.copy()
    for j in range(n):
        F[j, 0] += shift
    for j in range(n):
        if not F[j, 0] > 0.0:
            return F, j + 1
        inv = 1.0 / F[j, 0]
        F[j, 0] = inv
        kn = min(kd, n - 1 - j)
        for q in range(1, kn + 1):
            t = -F[j, q] * inv
            for p in range(q, kn + 1):
                F[j + q, p - q] += F[j, p] * t
            F[j, q] = -t
    return F, 0


def _merged_band(rng, n_nodes):
    """A restricted Hessian with long held runs of drops (wide band, few long columns)."""
    hb = rng.standard_normal((BANDWIDTH + 1, 2 * n_nodes))
    hb[0] = np.abs(hb[0]) + 4.0 * (BANDWIDTH + 1)
    free = np.ones(n_nodes - 1, dtype=bool)
    free[0] = False
    free[5:25] = False                  # a run of 20 held drops
    free[40:44] = False
    dof_map, n_red = step.reduced_indices(n_nodes, free)
    return bordered.restrict(hb, dof_map, n_red, 0)[0].T


@pytest.mark.parametrize("seed", range(4))
def test_factor_is_the_full_band_elimination_bit_for_bit_on_wide_bands(seed):
    rng = np.random.default_rng(seed)
    ab = _merged_band(rng, 60)
    assert ab.shape[0] - 1 > 20                              # the band is wide
    ends = banded.envelope(ab)
    assert np.sum(ends) < 0.5 * ab.shape[1] * (ab.shape[0] - 1)  # most columns are short
    shift = float(rng.uniform(0.0, 1.0))
    At = np.ascontiguousarray(ab.T)
    F, _, info = banded.factor_rows(At, shift)
    F_ref, info_ref = _full_band_factor(At, shift)
    assert info == info_ref == 0
    assert np.array_equal(F, F_ref)
    shifted = ab.copy()
    shifted[0] += shift
    L = banded.factor(ab, shift)[0]
    np.testing.assert_allclose(L, dpbtrf(shifted, lower=1)[0], rtol=1e-12, atol=1e-13)
    for j, e in enumerate(ends):                             # zero below the envelope
        assert not np.any(F_ref[j, e + 1:])
    b = rng.standard_normal(ab.shape[1])
    x = banded.solve_factored(L, b)
    dense = np.zeros((ab.shape[1],) * 2)
    for k in range(ab.shape[0]):
        for j in range(ab.shape[1] - k):
            dense[j + k, j] = dense[j, j + k] = ab[k, j]
    np.testing.assert_allclose((dense + shift * np.eye(len(b))) @ x, b, rtol=0, atol=1e-10)


def test_an_indefinite_wide_band_fails_where_the_full_elimination_does():
    ab = _merged_band(np.random.default_rng(7), 60)
    ab[0, 30] = -1e3
    assert banded.factor(ab, 0.0)[1] == _full_band_factor(np.ascontiguousarray(ab.T), 0.0)[1] > 0


@pytest.mark.parametrize("design", [(40.0, 1.0), (100.0, 1.0)])
def test_factor_and_solve_equal_the_full_band_ones_on_solver_states(design):
    """Real restricted Hessians along a solve, including iterations with flat stretches."""
    widest = 0
    for hb, grad, free in solver_states(design, range(0, 20)):
        dof_map, n_red = step.reduced_indices(grad.size // 2, free)
        ab = bordered.restrict(hb, dof_map, n_red, 0)[0].T
        widest = max(widest, ab.shape[0] - 1)
        shift = 1e-3 * np.abs(ab[0]).mean()
        At = np.ascontiguousarray(ab.T)
        F, ends, info = banded.factor_rows(At, shift)
        F_ref, info_ref = _full_band_factor(At, shift)
        assert info == info_ref
        if info == 0:
            assert np.array_equal(F, F_ref)
            rhs = -grad[dof_map >= 0][:n_red] if n_red else np.zeros(0)
            x = banded.solve_rows(F, ends, rhs)
            assert np.all(np.isfinite(x))
    assert widest > 20
