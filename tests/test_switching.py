"""Switching force from the shell reference: sign, energy balance, trend with d and p."""
import json

import numpy as np
import pytest
from click.testing import CliRunner

from stitchswitch import Patch
from stitchswitch.cli.main import cli
from stitchswitch.fem_reference.switching import switching_curve


@pytest.fixture(scope="module")
def curves():
    return {dp: switching_curve(Patch(*dp), steps=12, elements_inside=20)
            for dp in [(40.0, 0.7), (40.0, 0.9), (70.0, 0.7), (70.0, 0.9)]}


def test_curve_starts_at_equilibrium_and_resists(curves):
    for c in curves.values():
        assert c.converged.all()
        assert abs(c.force[0]) < 1e-6 * max(abs(c.force).max(), 1e-12)     # F = 0 at pop-up
        assert np.all(c.force[1:-1] < 0)                                    # pushing costs energy
        assert c.barrier > 0 and c.switching_force > 0


def test_switching_force_increases_with_diameter_and_fill(curves):
    f = {k: c.switching_force for k, c in curves.items()}
    assert f[(40.0, 0.9)] > f[(40.0, 0.7)] and f[(70.0, 0.9)] > f[(70.0, 0.7)]
    assert f[(70.0, 0.7)] > f[(40.0, 0.7)] and f[(70.0, 0.9)] > f[(40.0, 0.9)]


def test_cli_writes_curve_and_plot(tmp_path):
    result = CliRunner().invoke(cli, ["switch-force", "-d", "50", "-p", "0.8", "--steps", "8",
                                      "--csv", str(tmp_path / "c.csv"), "--plot", str(tmp_path / "c.png"), "--json"])
    assert result.exit_code == 0, result.output
    out = json.loads(result.output)
    assert out["switching_force"] > 0 and out["energy_barrier"] > 0
    assert (tmp_path / "c.png").read_bytes()[:4] == b"\x89PNG"
    assert len((tmp_path / "c.csv").read_text().splitlines()) == 2 + 9
