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


def synthetic_map(nd=4, npp=3, nodes=30):
    """A small ``DesignMap`` of made-up smooth tables (no solve), for the map file's loader:
    the default material, diameters 40, 41, ... mm and fills 0.7, 0.75, ..."""
    from stitchswitch.reduced.design_space.design_map import DesignMap
    from stitchswitch.reduced.model.material_io import material_hash
    from stitchswitch.reduced.model.params import DEFAULT_MATERIAL

    d, p = 40.0 + np.arange(nd), 0.7 + 0.05 * np.arange(npp)
    dd, pp = np.meshgrid(d, p, indexing="ij")
    tables = {name: (k + 1.0) * (0.1 * dd + pp) for k, name in enumerate(
        ("h_mm", "r_a_mm", "z_a_mm", "r_b_mm", "z_b_mm", "energy"))}
    s = np.linspace(0.0, 1.0, nodes)
    profile = np.broadcast_to(np.sin(np.pi * s) * (0.01 * dd + pp)[..., None], (nd, npp, nodes))
    n_inside = np.full(nd, nodes // 2)
    return DesignMap(diameter_mm=d, fill=p, residual=np.full((nd, npp), 1e-12),
                     converged=np.ones((nd, npp), bool), u_mm=profile.astype(np.float32),
                     z_prof_mm=(2 * profile).astype(np.float32),
                     dr_mm=d / (2 * DEFAULT_MATERIAL.eta * n_inside), n_inside=n_inside,
                     material=DEFAULT_MATERIAL, material_hash=material_hash(DEFAULT_MATERIAL),
                     flags=np.zeros((nd, npp), np.int8), **tables)


def unwritable_dir(tmp_path):
    """A folder this process cannot create files in: a chmod 555 folder for a normal user;
    for root (which ignores the mode) /sys, which the kernel keeps read-only. Skips the test
    if there is none."""
    import os

    import pytest

    folder = tmp_path / "read-only"
    folder.mkdir()
    folder.chmod(0o555)
    for candidate in (folder, pathlib.Path("/sys")):
        probe = candidate / f".stitchswitch-probe-{os.getpid()}"
        try:
            probe.write_text("x")
        except OSError:
            return candidate
        probe.unlink()
    pytest.skip("no unwritable folder on this machine")


def solver_states(design, iterations):
    """The Newton solver's states along a cold solve of ``design`` (d_mm, fill) after each of
    ``iterations``: yields (hb, grad, free), the banded Hessian, the gradient and the free
    drops there (the systems the Newton step solves)."""
    from stitchswitch import DEFAULT_MATERIAL, Patch
    from stitchswitch.reduced.model.discretization import make_grid
    from stitchswitch.reduced.model.terms import ALL_TERMS
    from stitchswitch.reduced.model.terms.segment import BANDWIDTH
    from stitchswitch.reduced.solvers import continuation, fused, newton_loop, step

    grid = make_grid(Patch(*design), DEFAULT_MATERIAL)
    coef = fused.coefficients(ALL_TERMS, grid)
    r0, z0 = continuation.released_state(grid)
    n = r0.size
    for k in iterations:
        r, z = newton_loop.fused_iterate(r0.copy(), z0.copy(), coef, 0.0, k, 0, 0.0)[:2]
        grad, hb = np.zeros(2 * n), np.zeros((BANDWIDTH + 1, 2 * n))
        fused.derivatives(r, z, coef, grad, hb, True)
        yield hb, grad, step.stationarity(grad, np.maximum(z[:-1] - z[1:], 0.0))[1]


def cli_run(*args):
    """Invoke the ``stitchswitch`` CLI in-process with every argument as a string."""
    from click.testing import CliRunner

    from stitchswitch.cli.main import cli

    return CliRunner().invoke(cli, [str(a) for a in args])


def panel_design(tmp_path, *place_args):
    """A design file with one 300 x 200 mm rectangle named ``panel`` (``import``), and, given
    ``place_args``, ``place`` run on it with those arguments."""
    path = tmp_path / "d.json"
    assert cli_run("import", "--rectangle", "300x200", "--name", "panel", "-o", path).exit_code == 0
    if place_args:
        assert cli_run("place", path, "--piece", "panel", *place_args).exit_code == 0
    return path
