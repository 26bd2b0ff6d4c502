"""Shared test helpers: random admissible states and finite-difference derivatives.

Imported as ``helpers`` (``pythonpath = ["tests"]`` in pyproject.toml), so that ``pytest`` and
``python -m pytest`` collect the same tests.
"""
import pathlib

import numpy as np

#: the external fixtures shipped with the repository (tests/data/external/README.md)
EXTERNAL = pathlib.Path(__file__).resolve().parent / "data" / "external"


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


def fd_jacobian(f, x, h=1e-6):
    """Central finite-difference Jacobian of the vector function f at x: row k is d f_k / d x
    (for a gradient f, the Hessian)."""
    cols = []
    for k in range(x.size):
        e = np.zeros_like(x)
        e[k] = h
        cols.append((f(x + e) - f(x - e)) / (2 * h))
    return np.array(cols).T
