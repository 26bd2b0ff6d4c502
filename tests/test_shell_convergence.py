"""The shell of revolution converges at the theoretical order on an analytic problem.

A clamped circular plate (radius a, rigidity D, Poisson 0.3) under a small uniform pressure q:
the linear solution w = -q (a^2 - rho^2)^2 / (64 D) has the total potential (per radian)
-q^2 a^6 / (768 D). Cubic Hermite elements for this fourth-order problem converge in energy at
order 2 (k - 1) = 4 for k = 3. The shell is the full nonlinear code (membrane, hoop bending, the
double node at a / 2 with its stretch unknown), so the test measures its own discretization: the
order from the differences of the energy on nested meshes, and the energy against the linear
plate within the small-deflection error (w / t ~ 0.1).
"""
import numpy as np

from stitchswitch.fem_reference.revolution.meridian import Meridian
from stitchswitch.fem_reference.revolution.moduli import Moduli
from stitchswitch.fem_reference.revolution.newton import minimize
from stitchswitch.fem_reference.revolution.problem import ShellProblem

A_MM, D, MEMBRANE, NU, Q = 10.0, 1.0, 12.0, 0.3, 6.4e-4     # plate thickness 1 mm: A = 12 D


def _plate_energy(refine):
    m = Moduli(lam=1.0, a_s=MEMBRANE, a_t=MEMBRANE, coupling=NU * MEMBRANE, bending=D,
               compression=1.0, jam=0.0, c_jam=0.0, w_log=0.0, gamma_mm=1.0, kappa0_per_mm=0.0,
               relaxed=False, hoop_bending=True, nu=NU)
    mer = Meridian(A_MM / 2, A_MM, 2, 1.0, 8, refine=refine)
    problem = ShellProblem(mer, m, m, edge="clamped", pressure=Q)
    res = minimize(problem, problem.flat_state(), tol=1e-11)
    assert res.converged
    return res.energy, mer.node_values(res.y)[2][0]


def test_clamped_plate_energy_converges_at_order_four():
    E = np.array([_plate_energy(k)[0] for k in range(4)])
    d = np.abs(np.diff(E))
    orders = np.log2(d[:-1] / d[1:])
    assert np.all(np.abs(orders - 4.0) <= 0.1), orders
    exact = -Q ** 2 * A_MM ** 6 / (768 * D)
    assert abs(E[-1] / exact - 1) < 0.005
    apex = _plate_energy(2)[1]
    assert abs(apex / (-Q * A_MM ** 4 / (64 * D)) - 1) < 0.01
