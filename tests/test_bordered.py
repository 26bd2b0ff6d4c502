"""The bordered-band Newton system (``solvers.bordered``) against dense linear algebra, and the
Newton direction it gives against the node-by-node numbering's on real solver states."""
import numpy as np
import pytest

from stitchswitch.reduced.model.terms.segment import BANDWIDTH
from stitchswitch.reduced.solvers import banded, bordered, step

from helpers import solver_states


def _dense_restricted(hb, dof_map, n_red):
    kmax, n = hb.shape
    H = np.zeros((n, n))
    for k in range(kmax):
        for j in range(n - k):
            H[j + k, j] = H[j, j + k] = hb[k, j]
    P = np.zeros((n, n_red))
    for a, v in enumerate(dof_map):
        if v >= 0:
            P[a, v] = 1.0
    return P.T @ H @ P


def _free_drops(rng, n):
    """Free-drop masks with long held runs (border groups), short ones and single nodes."""
    free = np.ones(n - 1, dtype=bool)
    i = 1
    while i < n - 1:
        run = rng.choice([0, 0, 1, 2, 5, 12])
        free[i:i + run] = False
        i += run + 1 + rng.integers(0, 3)
    free[0] = False
    return free


def _random_band(rng, n, spd=True):
    hb = rng.standard_normal((BANDWIDTH + 1, 2 * n))
    hb[0] = np.abs(hb[0]) + (3.0 * (BANDWIDTH + 1) if spd else 0.0)
    return hb


@pytest.mark.parametrize("seed", range(8))
def test_bordered_solve_matches_a_dense_solve_with_merged_groups(seed):
    rng = np.random.default_rng(seed)
    n = int(rng.integers(20, 80))
    free = _free_drops(rng, n)
    dof_map, n_band, m = bordered.indices(n, free)
    old_map, n_red = step.reduced_indices(n, free)
    assert n_band + m == n_red and m > 0
    assert sorted(set(dof_map[dof_map >= 0])) == list(range(n_red))
    # the same variables: one bijection between the two numberings
    assert len({(a, b) for a, b in zip(old_map, dof_map)}) == len(set(old_map))
    hb = _random_band(rng, n)
    At, B, C = bordered.restrict(hb, dof_map, n_band, m)
    assert At.shape[1] - 1 <= BANDWIDTH + 2 * bordered.MAX_BAND_SPAN
    A = _dense_restricted(hb, dof_map, n_red)
    np.testing.assert_allclose(A[:n_band, n_band:].T, B, rtol=1e-14, atol=1e-13)
    np.testing.assert_allclose(A[n_band:, n_band:], C, rtol=1e-14, atol=1e-13)
    shift = float(rng.uniform(0.0, 2.0))
    *factors, info = bordered.factor(At, B, C, shift)
    assert info == 0
    rhs = rng.standard_normal(n_red)
    x = bordered.solve(*factors, rhs)
    expected = np.linalg.solve(A + shift * np.eye(n_red), rhs)
    np.testing.assert_allclose(x, expected, rtol=1e-11, atol=1e-12 * np.abs(expected).max())


@pytest.mark.parametrize("seed", range(6))
def test_bordered_factorization_fails_exactly_when_the_matrix_is_indefinite(seed):
    rng = np.random.default_rng(100 + seed)
    n = 40
    free = _free_drops(rng, n)
    dof_map, n_band, m = bordered.indices(n, free)
    hb = _random_band(rng, n, spd=False)
    At, B, C = bordered.restrict(hb, dof_map, n_band, m)
    A = _dense_restricted(hb, dof_map, n_band + m)
    lam = np.linalg.eigvalsh(A)[0]
    for shift in (-lam - 1e-6 * abs(lam), -lam + 1e-6 * abs(lam)):
        definite = bool(lam + shift > 0)
        assert (bordered.factor(At, B, C, shift)[5] == 0) == definite


def _old_direction(ab, g, dof_map, n_red, shift):
    """The banded Newton direction in the node-by-node numbering of ``step.reduced_indices``."""
    g_red = np.zeros(n_red)
    for a in range(g.size):
        if dof_map[a] >= 0:
            g_red[dof_map[a]] -= g[a]
    L, info = banded.factor(ab, shift)
    assert info == 0
    x = banded.solve_factored(L, g_red)
    return np.where(dof_map >= 0, x[np.maximum(dof_map, 0)], 0.0)


@pytest.mark.parametrize("design", [(55.0, 1.0), (85.0, 1.0), (25.0, 1.0)])
def test_newton_direction_equals_the_node_by_node_numberings_on_solver_states(design):
    borders = 0
    for hb, grad, free in solver_states(design, range(1, 25, 3)):
        n = grad.size // 2
        old_map, n_red = step.reduced_indices(n, free)
        ab_old = bordered.restrict(hb, old_map, n_red, 0)[0].T
        dof_map, n_band, m = bordered.indices(n, free)
        At, B, C = bordered.restrict(hb, dof_map, n_band, m)
        borders += m
        shift = 0.0
        while banded.factor(ab_old, shift)[1] != 0:
            shift = max(10.0 * shift, 1e-10 * np.abs(ab_old[0]).mean())
        d, used, _ = step.direction(At, B, C, grad, dof_map, 10.0 * shift, False)
        assert used == pytest.approx(shift, rel=1e-15)
        # kept: the search starts at the given shift, not a decade below it
        kept, used_kept, raised = step.direction(At, B, C, grad, dof_map, shift, True)
        assert used_kept == shift and not raised
        np.testing.assert_array_equal(kept, d)
        expected = _old_direction(ab_old, grad, old_map, n_red, shift)
        # equal to round-off: the forward error bound of a backward-stable solve, cond * eps
        cond = np.linalg.cond(_dense_restricted(hb, old_map, n_red) + shift * np.eye(n_red))
        tol = 10.0 * cond * np.finfo(float).eps * np.abs(expected).max()
        np.testing.assert_allclose(d, expected, rtol=0, atol=tol)
    assert borders > 0


def test_the_shift_search_reports_whether_it_raised_its_first_trial():
    """An indefinite restricted Hessian: the first trial (the given shift kept) fails, the
    search raises it tenfold until the factor succeeds and says so."""
    rng = np.random.default_rng(3)
    n = 30
    free = np.ones(n - 1, dtype=bool)
    free[0] = False
    hb = _random_band(rng, n, spd=False)
    dof_map, n_band, m = bordered.indices(n, free)
    At, B, C = bordered.restrict(hb, dof_map, n_band, m)
    grad = rng.standard_normal(2 * n)
    start = 1e-3
    assert bordered.factor(At, B, C, start)[5] != 0
    d, used, raised = step.direction(At, B, C, grad, dof_map, start, True)
    assert raised and used > start and np.all(np.isfinite(d))
    assert bordered.factor(At, B, C, used)[5] == 0 != bordered.factor(At, B, C, used / 10.0)[5]
    _, again, raised_again = step.direction(At, B, C, grad, dof_map, used, True)
    assert again == used and not raised_again
