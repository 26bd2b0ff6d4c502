import numpy as np
import pytest

from stitchswitch.reduced.model.discretization import make_grid
from stitchswitch.reduced.model.params import DEFAULT_MATERIAL, Patch


@pytest.fixture
def small_grid():
    """A 40-node grid (N_in = 12) with every term active: hardening strong enough to matter."""
    material = DEFAULT_MATERIAL.replace(n_nodes=40, w_log=0.5, gamma_mm=1.0)
    return make_grid(Patch(20.0, 0.8), material)


def random_state(grid, seed, slack=True):
    """A random admissible-looking configuration with taut and slack segments (dR units)."""
    rng = np.random.default_rng(seed)
    n = grid.n_nodes
    steps = rng.uniform(0.3 if slack else 1.0, 1.9, n - 1)     # some segments shorter than lambda
    r = np.concatenate([[0.0], np.cumsum(steps)])
    drops = rng.uniform(0.0, 0.9, n - 1)
    drops[0] = 0.0
    z = np.concatenate([np.cumsum(drops[::-1])[::-1], [0.0]])
    return r, z


def pack(r, z):
    """Interleave r and z into the solver's dof vector (r0, z0, r1, z1, ...)."""
    x = np.empty(2 * r.size)
    x[0::2], x[1::2] = r, z
    return x


def fd_gradient(f, x, h=1e-6):
    """Central finite-difference gradient of the scalar function f at x."""
    g = np.empty_like(x)
    for k in range(x.size):
        e = np.zeros_like(x)
        e[k] = h
        g[k] = (f(x + e) - f(x - e)) / (2 * h)
    return g
