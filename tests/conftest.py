import pytest

from stitchswitch.reduced.model.discretization import make_grid
from stitchswitch.reduced.model.params import DEFAULT_MATERIAL, Patch


@pytest.fixture
def small_grid():
    """A 40-node grid (N_in = 12) with every term active: hardening strong enough to matter."""
    material = DEFAULT_MATERIAL.replace(n_nodes=40, w_log=0.5, gamma_mm=1.0)
    return make_grid(Patch(20.0, 0.8), material)


@pytest.fixture(scope="session")
def _cache_dir(tmp_path_factory):
    return tmp_path_factory.mktemp("stitchswitch-cache")


@pytest.fixture(autouse=True)
def _private_cache(_cache_dir, monkeypatch):
    """Every test writes design maps and other caches into a temporary folder, never into the
    user's home (``STITCHSWITCH_CACHE``); one folder for the session, so a map is built once."""
    monkeypatch.setenv("STITCHSWITCH_CACHE", str(_cache_dir))
