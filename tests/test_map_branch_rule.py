"""The design map's branch rule where two branches coexist does not depend on round-off.

Inside the band where the dome and the overhanging neck coexist (docs/design-map.md), which
branch a cold solve lands on is decided by its path down to round-off: a relative perturbation
of 1e-12 of the released state moved 3 of these rows' band points from one branch to the other
when the map took the cold solve's branch there. The map's rule (the branch continuation along
increasing fill reaches, ``precompute._sweep``) must give the same branches whatever that
round-off, in the cold start of each row and in every warm start along it.
"""
import numpy as np
import pytest

from stitchswitch import DEFAULT_MATERIAL
from stitchswitch.reduced.design_space import precompute
from stitchswitch.reduced.solvers import continuation
from stitchswitch.reduced.solvers import solve as solve_module

#: Rows through the band, among them every row whose branch a change of the solver's path moved.
ROWS_MM = (43.0, 54.0, 67.0, 77.0, 79.0, 81.0, 83.0)
#: The soft mode moves h on one branch by less than this (tests/test_default_map.py).
SOFT_H_MM = 1e-4


def _row(d):
    rows = precompute._solve_row((d, precompute.DEFAULT_FILLS.tolist(), DEFAULT_MATERIAL, True))[0]
    return np.array(rows["h_mm"]), np.array(rows["energy"])


@pytest.fixture(scope="module")
def unperturbed():
    return {d: _row(d) for d in ROWS_MM}


@pytest.mark.parametrize("eps", [1e-12, -1e-12, 1e-9])
def test_a_round_off_perturbation_of_the_start_keeps_every_branch(unperturbed, eps, monkeypatch):
    released, warm = continuation.released_state, solve_module._warm_profile

    def perturbed_release(grid, fraction=continuation.SEED_FRACTION):
        r, z = released(grid, fraction)
        return r * (1 + eps), z * (1 + eps)

    def perturbed_warm(start, grid):
        r, z = warm(start, grid)
        return r * (1 + eps), z * (1 + eps)

    monkeypatch.setattr(continuation, "released_state", perturbed_release)
    monkeypatch.setattr(solve_module, "_warm_profile", perturbed_warm)
    for d in ROWS_MM:
        h, energy = _row(d)
        h0, energy0 = unperturbed[d]
        assert np.abs(h - h0).max() <= SOFT_H_MM, d
        assert energy == pytest.approx(energy0, rel=1e-12)


def test_such_perturbations_move_cold_solves_inside_the_band(unperturbed, monkeypatch):
    """The perturbations above are not too small to matter: they move cold solves of these
    rows' designs just before the dome's fold from one branch to the other."""
    from stitchswitch import Patch, solve

    released = continuation.released_state
    fills = precompute.DEFAULT_FILLS
    near_fold = []
    for d in ROWS_MM:
        jump = int(np.flatnonzero(np.diff(unperturbed[d][0]) > 1.0)[0]) + 1
        near_fold += [(d, float(fills[j])) for j in range(jump - 3, jump)]
    moved = 0
    for eps in (0.0, 1e-12, -1e-12, 1e-9):
        monkeypatch.setattr(continuation, "released_state",
                            lambda grid, fraction=continuation.SEED_FRACTION, e=eps: tuple(
                                a * (1 + e) for a in released(grid, fraction)))
        h = np.array([solve(Patch(d, p)).keypoints.h_mm for d, p in near_fold])
        if eps == 0.0:
            h0 = h
        moved += int(np.sum(np.abs(h - h0) > 1.0))
    assert moved >= 1
