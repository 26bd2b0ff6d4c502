"""The shell of revolution's derivatives against central finite differences: the jets, every
constitutive law (taut, meridian-relaxed, Pipkin-relaxed, jamming, hardening, bending with and
without hoop bending and natural curvature), and the assembled energy with the interface map,
the loads and the boundary conditions."""
import numpy as np
import pytest

from stitchswitch.fem_reference.revolution import constitutive
from stitchswitch.fem_reference.revolution.jet import Jet
from stitchswitch.fem_reference.revolution.kinematics import strains
from stitchswitch.fem_reference.revolution.meridian import Meridian
from stitchswitch.fem_reference.revolution.moduli import Moduli, region_moduli
from stitchswitch.fem_reference.revolution.params import ShellParams
from stitchswitch.fem_reference.revolution.problem import ShellProblem
from stitchswitch.reduced.model.params import DEFAULT_MATERIAL, Patch


def _moduli(relaxed, hoop, nu, kappa0=0.0):
    a_s, a_t = 0.8, 1.1
    return Moduli(lam=1.3, a_s=a_s, a_t=a_t, coupling=nu * np.sqrt(a_s * a_t), bending=0.2,
                  compression=0.05, jam=0.6, c_jam=0.8, w_log=0.4, gamma_mm=3.0,
                  kappa0_per_mm=kappa0, relaxed=relaxed, hoop_bending=hoop, nu=nu)


def _points(n=400, seed=0):
    rng = np.random.default_rng(seed)
    q = np.array([rng.uniform(0.5, 6, n), rng.uniform(0.1, 2.2, n), rng.uniform(-1.8, 1.0, n),
                  rng.uniform(-1, 1, n), rng.uniform(-1, 1, n), rng.uniform(-2, 2, n)])
    S = rng.uniform(0.5, 4, n)
    return q, S


def _density(q, S, m):
    eps_s, eps_t, k_s, k_t = strains(q, S, m.lam)
    w = constitutive.membrane(eps_s, eps_t, m) + constitutive.bending(k_s, k_t, m)
    return w * (m.lam ** 2 * S) + constitutive.hoop_hardening(eps_t, S, m)


def _kinks(q, S, m, eps):
    """Points within eps of a switch of the piecewise laws (central differences straddle it)."""
    eps_s, eps_t, _, _ = strains(q, S, m.lam)
    a, b = eps_s.v, eps_t.v
    ns, nt = m.a_s * a + m.coupling * b, m.a_t * b + m.coupling * a
    near = [a, b, ns, nt, a + 1 - m.jam]
    return np.any([np.abs(x) < 1e3 * eps for x in near], axis=0)


@pytest.mark.parametrize("relaxed, hoop, nu, kappa0", [
    (False, False, 0.0, 0.0), (False, True, 0.3, 0.0), (True, True, 0.3, 0.05),
    (True, False, 0.45, -0.1)])
def test_pointwise_density_derivatives(relaxed, hoop, nu, kappa0):
    m = _moduli(relaxed, hoop, nu, kappa0)
    q, S = _points()
    f = _density(q, S, m)
    eps = 1e-6
    keep = ~_kinks(q, S, m, eps)
    eps_s, eps_t, _, _ = strains(q, S, m.lam)
    # the sample covers every branch: taut, wrinkled either way, slack, jammed
    a, b = eps_s.v, eps_t.v
    assert np.any((a > 0) & (b > 0)) and np.any((a < 0) & (b < 0)) and np.any(a < m.jam - 1)
    assert np.any((a > 0) & (b < -0.3)) and np.any((b > 0) & (a < -0.3))
    for k in range(6):
        dq = np.zeros_like(q)
        dq[k] = eps
        fp, fm = _density(q + dq, S, m), _density(q - dq, S, m)
        np.testing.assert_allclose(f.g[k][keep], ((fp.v - fm.v) / (2 * eps))[keep], rtol=1e-6, atol=1e-7)
        np.testing.assert_allclose(f.h[:, k][:, keep], ((fp.g - fm.g) / (2 * eps))[:, keep],
                                   rtol=1e-5, atol=1e-6)
    np.testing.assert_allclose(f.h, f.h.transpose(1, 0, 2), atol=1e-12)


def test_jet_arithmetic():
    rng = np.random.default_rng(1)
    q = rng.uniform(0.5, 2.0, (3, 20))
    x, y, z = (Jet.variable(q, k) for k in range(3))

    def value(q):
        x, y, z = q
        return (x * y + 3.0) / z ** 1.5 - np.sqrt(x) * 2.0 + (y - 1.2).clip(0) ** 2

    f = (x * y + 3.0) / z.power(1.5) - x.sqrt() * 2.0 + (y - 1.2).positive_square()
    np.testing.assert_allclose(f.v, value(q))
    eps = 1e-6
    for k in range(3):
        dq = np.zeros_like(q)
        dq[k] = eps
        np.testing.assert_allclose(f.g[k], (value(q + dq) - value(q - dq)) / (2 * eps), rtol=1e-6)


def test_pipkin_relaxation_carries_no_compression():
    m = _moduli(True, True, 0.3)
    m0 = Moduli(**{**m.__dict__, "compression": 0.0, "c_jam": 0.0})
    a = Jet.variable(np.array([[-0.2, 0.1, -0.05]]), 0)
    b = Jet.variable(np.array([[-0.1, -0.5, 0.2]]), 0)
    w = constitutive.membrane(a, b, m0).v
    assert w[0] == 0.0                                          # slack both ways
    # hoop wrinkled: the uniaxial meridional energy, below the taut energy
    taut = 0.5 * (m.a_s * 0.01 + m.a_t * 0.25) + m.coupling * 0.1 * -0.5
    assert 0.0 < w[1] < taut
    np.testing.assert_allclose(w[1], 0.5 * (m.a_s - m.coupling ** 2 / m.a_t) * 0.01)


@pytest.mark.parametrize("edge", ["free", "held", "clamped"])
def test_assembled_energy_derivatives(edge):
    patch = Patch(40.0, 0.9)
    inner, outer = region_moduli(patch, DEFAULT_MATERIAL, ShellParams(kappa0_per_mm=0.02))
    mer = Meridian(patch.diameter_mm / 3.4, 40.0, 6, 1.3, 6)
    problem = ShellProblem(mer, inner, outer, edge=edge, pressure=0.01, weight=0.003)
    rng = np.random.default_rng(2)
    y = problem.flat_state() + 0.05 * rng.standard_normal(mer.size)
    y[mer.s_index] = 0.7
    flat = problem.flat_state()
    y[problem.fixed] = flat[problem.fixed]
    E, g, H = problem.derivatives(y)
    assert np.isfinite(E)
    h = 1e-6
    for k in range(mer.size):
        e = np.zeros(mer.size)
        e[k] = h
        fd = (problem.energy(y + e) - problem.energy(y - e)) / (2 * h)
        np.testing.assert_allclose(g[k], fd, rtol=1e-5, atol=1e-7)
        hd = (problem.derivatives(y + e)[1] - problem.derivatives(y - e)[1]) / (2 * h)
        np.testing.assert_allclose(H[:, [k]].toarray().ravel(), hd, rtol=1e-4, atol=1e-6)
    np.testing.assert_allclose((H - H.T).toarray(), 0.0, atol=1e-10)
