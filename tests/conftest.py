import numpy as np
import pytest

from stitchswitch.reduced.discretization import make_grid
from stitchswitch.reduced.params import DEFAULT_MATERIAL, Patch


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
