"""The shell's certificate of a strict local minimum where the scaled Hessian's lowest eigenvalue
is at the eigensolver's round-off: the energy's second difference along the lowest mode.

d 25 mm, p 1.0 settles flat; its flat state's lowest scaled eigenvalue is 1e-15 to 2e-13
depending on the BLAS kernel's round-off (both sides of the 1e-13 threshold), while the energy
along its mode rises cleanly both ways.
"""
import numpy as np
import pytest

from stitchswitch import DEFAULT_MATERIAL, Patch
from stitchswitch.fem_reference.revolution.newton import (
    MIN_EIGENVALUE,
    lowest_modes,
    minimize,
    mode_curvature,
    resolved_curvature,
)
from stitchswitch.fem_reference.revolution.solve import (
    MODE_AMPLITUDE,
    build,
    equilibrium,
    reduced_start,
    relax,
)


@pytest.fixture(scope="module")
def flat_d25():
    problem = build(Patch(25.0, 1.0))
    res = minimize(problem, problem.flat_state(), max_iter=300)
    assert res.converged
    return problem, res.y


def test_the_second_difference_is_the_hessian_along_a_resolved_mode(flat_d25):
    """Along the second mode (eigenvalue ~1e-9, resolved), the energy's second difference equals
    v^T H v a^2 to the difference's truncation error."""
    problem, y = flat_d25
    _, V = lowest_modes(problem, y, 2)
    v = V[1] / np.max(np.abs(V[1]))
    _, _, H = problem.derivatives(y)
    f = problem.free
    quad = float(v[f] @ (H[f][:, f] @ v[f]))
    for a in (1e-3, 1e-2):
        assert mode_curvature(problem, y, v, a) == pytest.approx(quad * a * a, rel=1e-3)


def test_the_flat_state_rises_along_its_round_off_mode(flat_d25):
    problem, y = flat_d25
    (mu, mu2), (v, _) = lowest_modes(problem, y, 2)
    assert abs(mu) < 1e-12                       # at or near the eigensolver's round-off
    assert mu2 > 1e3 * MIN_EIGENVALUE            # a clear gap to the next mode
    a = MODE_AMPLITUDE * problem.meridian.rb
    c = mode_curvature(problem, y, v, a)
    assert c > 1e4 * np.finfo(float).eps * problem.energy(y)
    assert resolved_curvature(problem, y, v, a)
    # quadratic: ten times the amplitude, a hundred times the rise
    assert mode_curvature(problem, y, v, 10 * a) == pytest.approx(100 * c, rel=0.02)


def test_negative_curvature_falls_along_its_mode():
    """d 25 mm, p 1.0 from the reduced guess: after 20 Newton steps the Hessian is indefinite
    (docs/fem-reference.md). At a finite amplitude a higher-order term can make the energy rise
    along the lowest mode; the quadratic check (a against a / 10) does not let that certify."""
    patch = Patch(25.0, 1.0)
    problem = build(patch)
    y = minimize(problem, reduced_start(problem, patch, DEFAULT_MATERIAL), max_iter=20).y
    (mu, _), (v, _) = lowest_modes(problem, y, 2)
    assert mu < -1e3 * MIN_EIGENVALUE
    a = MODE_AMPLITUDE * problem.meridian.rb
    # at a the rise is a higher-order term's (measured +2.1e-4); at a / 10 the curvature shows
    assert mode_curvature(problem, y, v, a) > 0.0
    assert mode_curvature(problem, y, v, 0.1 * a) < 0.0
    assert not resolved_curvature(problem, y, v, a)


def test_the_d25_fallback_certifies_on_any_kernel():
    st = equilibrium(Patch(25.0, 1.0))
    assert st.certified and abs(st.apex_mm) < 1e-6
    again = relax(st.problem, st.y)
    assert again.certified and np.max(np.abs(again.y - st.y)) < 1e-8
