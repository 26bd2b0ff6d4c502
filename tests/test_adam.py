"""The paper's projected Adam baseline (stitchswitch.reduced.solvers.adam)."""
from __future__ import annotations

import numpy as np
import pytest

from stitchswitch.errors import InvalidInputError
from stitchswitch.reduced.model import assembly
from stitchswitch.reduced.model.discretization import make_grid
from stitchswitch.reduced.model.params import DEFAULT_MATERIAL, Patch
from stitchswitch.reduced.solvers import adam, constraints, continuation
from stitchswitch.reduced.solvers.solve import solve

MATERIAL = DEFAULT_MATERIAL.replace(n_nodes=60)
PATCH = Patch(20, 0.9)
TOL = 1e-9


@pytest.fixture(scope="module")
def grid():
    return make_grid(PATCH, MATERIAL)


def start(grid):
    return grid.R.copy(), continuation.seed_bump(grid)


@pytest.fixture(scope="module")
def run300(grid):
    r0, z0 = start(grid)
    return adam.minimize(grid, r0, z0, tol=TOL, steps=300)


def test_energy_decreases_from_start(grid, run300):
    r0, z0 = constraints.project(*start(grid))
    e0 = assembly.energy(r0, z0, grid)
    assert np.isfinite(e0)
    assert np.isfinite(run300.energy)
    assert run300.energy < e0 - 1e-6 * abs(e0)
    # the reported energy is the energy of the returned (final) iterate
    assert run300.energy == pytest.approx(assembly.energy(run300.r, run300.z, grid), rel=1e-12)


@pytest.mark.parametrize("steps", [0, 1, 5, 300])
def test_returned_state_is_admissible(grid, run300, steps):
    if steps == 300:
        res = run300
    else:
        res = adam.minimize(grid, *start(grid), tol=TOL, steps=steps)
    assert res.r.shape == res.z.shape == (grid.n_nodes,)
    assert constraints.admissible(res.r, res.z, atol=1e-9)
    assert res.iterations == steps
    assert res.second_order is None


def test_state_is_admissible_from_inadmissible_start(grid):
    r0, z0 = start(grid)
    z0 = z0 + 0.3 * np.sin(np.arange(grid.n_nodes))      # breaks monotonicity and gauge
    res = adam.minimize(grid, r0, z0, tol=TOL, steps=20)
    assert constraints.admissible(res.r, res.z, atol=1e-9)


def test_deterministic(grid):
    a = adam.minimize(grid, *start(grid), tol=TOL, steps=100)
    b = adam.minimize(grid, *start(grid), tol=TOL, steps=100)
    assert np.array_equal(a.r, b.r) and np.array_equal(a.z, b.z)
    assert a.energy == b.energy and a.residual == b.residual
    assert a.message == b.message


def test_certificate_matches_newton_definition(grid, run300):
    g = assembly.gradient(run300.r, run300.z, grid)
    u = run300.z[:-1] - run300.z[1:]
    expected = constraints.kkt_residual(g[0::2], g[1::2], u)
    assert run300.residual == expected
    assert run300.converged == (run300.residual <= TOL)


def test_tiny_budget_is_not_converged(grid):
    res = adam.minimize(grid, *start(grid), tol=TOL, steps=5)
    assert res.iterations == 5
    assert res.converged is False
    assert res.residual > TOL
    assert "not converged" in res.message
    assert res.message.startswith("adam: 5 steps")


def test_loose_tolerance_reports_converged(grid):
    res = adam.minimize(grid, *start(grid), tol=1e6, steps=5)
    assert res.converged is True
    assert "(converged)" in res.message


@pytest.mark.parametrize("kwargs, name", [
    ({"steps": -1}, "steps"),
    ({"steps": 2.5}, "steps"),
    ({"steps": True}, "steps"),
    ({"lr": 0.0}, "lr"),
    ({"lr": -0.05}, "lr"),
    ({"lr": float("nan")}, "lr"),
    ({"clip": 0.0}, "clip"),
    ({"clip": -1.0}, "clip"),
    ({"beta1": 1.0}, "beta1"),
    ({"beta2": -0.1}, "beta2"),
    ({"eps": 0.0}, "eps"),
])
def test_invalid_arguments(grid, kwargs, name):
    with pytest.raises(InvalidInputError, match=name):
        adam.minimize(grid, *start(grid), tol=TOL, **kwargs)


def test_invalid_value_is_named(grid):
    with pytest.raises(InvalidInputError, match=r"lr: -0\.05"):
        adam.minimize(grid, *start(grid), tol=TOL, lr=-0.05)


def test_solve_with_adam(grid):
    sol = solve(PATCH, MATERIAL, solver="adam", max_iter=200)
    assert sol.solver == "adam"
    assert sol.iterations == 200
    assert sol.converged == (sol.residual <= sol.tol)
    assert sol.converged is False
    assert sol.second_order is None
    assert np.isfinite(sol.energy)
    assert constraints.admissible(sol.r_mm / sol.dr_mm, sol.z_mm / sol.dr_mm, atol=1e-9)
    assert "not converged" in sol.message
