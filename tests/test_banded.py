"""The compiled banded Cholesky of the Newton solver against LAPACK (scipy's dpbtrf/dpbtrs)."""
import numpy as np
import pytest
from scipy.linalg.lapack import dpbtrf, dpbtrs

from stitchswitch.reduced.solvers import banded


def _spd_band(rng, n, kd):
    """A random symmetric positive definite band (lower storage), diagonally dominant."""
    ab = rng.normal(size=(kd + 1, n))
    for k in range(1, kd + 1):
        ab[k, n - k:] = 0.0
    ab[0] = np.abs(ab[0]) + 2.0 * (kd + 1)
    return ab


@pytest.mark.parametrize("kd", [0, 1, 3, 5])
@pytest.mark.parametrize("seed", [0, 1, 2])
def test_factor_and_solve_match_lapack_on_random_spd_bands(kd, seed):
    rng = np.random.default_rng(seed)
    ab = _spd_band(rng, 200, kd)
    shift = float(rng.uniform(0.0, 1.0))
    shifted = ab.copy()
    shifted[0] += shift
    ref, info = dpbtrf(shifted, lower=1)
    assert info == 0
    before = ab.copy()
    L, info = banded.factor(ab, shift)
    assert info == 0
    np.testing.assert_allclose(L, ref, rtol=1e-13, atol=1e-14)
    b = rng.normal(size=200)
    x_ref, _ = dpbtrs(ref, b, lower=1)
    np.testing.assert_allclose(banded.solve(L, b), x_ref, rtol=1e-12, atol=1e-13)
    assert np.array_equal(ab, before)                     # the input band is not modified


@pytest.mark.parametrize("where", [0, 57, 199])
def test_an_indefinite_band_fails_like_dpbtrf(where):
    rng = np.random.default_rng(where)
    ab = _spd_band(rng, 200, 5)
    ab[0, where] = -50.0
    _, info_ref = dpbtrf(ab, lower=1)
    _, info = banded.factor(ab, 0.0)
    assert info == info_ref == where + 1
    assert banded.cholesky(ab) is None
    assert banded.cholesky(ab, 100.0) is not None      # a large enough shift makes it definite


def test_a_nan_band_is_reported_not_positive_definite():
    ab = _spd_band(np.random.default_rng(3), 20, 2)
    ab[0, 4] = np.nan
    assert banded.factor(ab, 0.0)[1] == 5
