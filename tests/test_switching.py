"""Snap-through by the contact plate (shell of revolution): the path reaches the inverted state,
every force is a converged contact reaction, and the switching force does not depend on the
step count."""
import json

import numpy as np
import pytest
from click.testing import CliRunner

from stitchswitch import Patch
from stitchswitch.cli.main import cli
from stitchswitch.fem_reference.snap import plate_radius_mm, switching_path
from stitchswitch.fem_reference.snap.states import held_problem, rim_mm


def test_plate_radius_rule_meets_the_papers_contact_areas():
    assert abs(np.pi * plate_radius_mm(20.0) ** 2 - 44.0) < 1e-9          # 0.44 cm^2
    assert abs(np.pi * plate_radius_mm(90.0) ** 2 - 1590.0) < 1e-9        # 15.9 cm^2
    assert plate_radius_mm(40.0) < plate_radius_mm(60.0)


def _check_inverted(path):
    assert path.popup.certified and path.final.certified
    assert path.inverted
    problem = held_problem(path.patch)
    assert path.final.apex_mm < rim_mm(problem, path.final.y)               # apex below the rim
    assert path.popup.apex_mm > 0 > path.final.apex_mm
    assert path.converged.all()
    # every sampled force is a contact reaction (>= 0), zero at the pop-up state, and the
    # switching force is where the curve peaks, not at the last step (no reset to flat)
    assert path.force[0] == 0.0 and np.all(path.force >= 0.0)
    assert 0 < np.argmax(path.force) < path.force.size - 1
    assert path.switching_force >= path.force.max() * (1 - 1e-9) and path.limit_point
    assert path.barrier > 0


@pytest.fixture(scope="module")
def path_60_08():
    return switching_path(Patch(60.0, 0.8))


def test_d60_p08_switches_to_the_inverted_state(path_60_08):
    _check_inverted(path_60_08)
    # both states have the same energy: kappa0 = 0 makes the energy symmetric in z
    assert abs(path_60_08.final.energy - path_60_08.popup.energy) < 1e-9 * abs(path_60_08.popup.energy)


def test_switching_force_does_not_depend_on_the_step_count(path_60_08):
    finer = switching_path(Patch(60.0, 0.8), steps=48)
    assert finer.inverted
    assert abs(finer.switching_force / path_60_08.switching_force - 1) < 0.02
    assert abs(finer.barrier / path_60_08.barrier - 1) < 0.1


@pytest.mark.slow
@pytest.mark.parametrize("d, p", [(90.0, 0.6), (80.0, 0.7), (70.0, 0.7), (60.0, 0.7), (50.0, 0.8)])
def test_other_designs_switch_to_the_inverted_state(d, p):
    _check_inverted(switching_path(Patch(d, p)))


#: the CLI tests check what the command prints and writes, not the physics (the tests above):
#: a coarse shell, 16 elements instead of 40, keeps each run to a third of the time
COARSE = ["--elements", "16"]


def test_cli_prints_newtons_and_the_verdict(tmp_path):
    result = CliRunner().invoke(cli, ["switch-force", "-d", "90", "-p", "0.6", *COARSE, "--csv",
                                      str(tmp_path / "c.csv"), "--plot", str(tmp_path / "c.png")])
    assert result.exit_code == 0, result.output
    assert "bistable" in result.output and " N at plate height" in result.output
    assert "model units" not in result.output
    assert (tmp_path / "c.png").read_bytes()[:4] == b"\x89PNG"
    lines = (tmp_path / "c.csv").read_text().splitlines()
    assert lines[1] == "w_mm,force_N" and len(lines) > 5


def test_cli_json_and_bad_input(tmp_path):
    result = CliRunner().invoke(cli, ["switch-force", "-d", "90", "-p", "0.6", *COARSE, "--json"])
    assert result.exit_code == 0, result.output
    out = json.loads(result.output)
    assert out["verdict"] == "bistable" and out["switching_force_n"] > 0
    assert out["switched"]["apex_mm"] < 0 < out["popup"]["h_mm"]
    bad = CliRunner().invoke(cli, ["switch-force", "-d", "5", "-p", "0.6"])
    assert bad.exit_code == 2 and "diameter_mm" in bad.output
    bad = CliRunner().invoke(cli, ["switch-force", "-d", "90", "-p", "0.6", "--csv", str(tmp_path)])
    assert bad.exit_code == 2 and "--csv" in bad.output
    flat = CliRunner().invoke(cli, ["switch-force", "-d", "25", "-p", "0.6"])
    assert flat.exit_code == 1 and "no certified pop-up state" in flat.output     # not bad input
