"""``stitchswitch sensitivity``: the table, --json equal to the library, bad input exits 2.

The command runs the paper's 25 designs; the tests make it run two (``CALIBRATION_DESIGNS``
is read when the command runs)."""
import json

import pytest
from click.testing import CliRunner

from stitchswitch.cli.main import cli
from stitchswitch.files.jsonsafe import json_safe
from stitchswitch.reduced.calibration import sensitivity as sens
from stitchswitch.reduced.model.material_io import save_material
from stitchswitch.reduced.model.params import DEFAULT_MATERIAL

DESIGNS = ((70.0, 1.0), (40.0, 0.8))


@pytest.fixture(autouse=True)
def _two_designs(monkeypatch):
    monkeypatch.setattr(sens, "CALIBRATION_DESIGNS", DESIGNS)


def run(*args):
    return CliRunner().invoke(cli, ["sensitivity", "--workers", "1", *args])


def test_table_has_a_row_per_parameter_and_keypoint():
    result = run()
    assert result.exit_code == 0, result.output
    lines = result.stdout.splitlines()
    assert "2 (d x p), step exp(+-0.05)" in result.stdout and "54 in" in result.stdout
    rows = [line.split() for line in lines if line.split()[:1] and line.split()[0] in sens.parameter_names()]
    assert len(rows) == len(sens.parameter_names()) * len(sens.KEYPOINTS)
    taut_and_slack_c = [r for r in rows if r[:2] == ["jam", "h_mm"]][0]
    assert taut_and_slack_c[-1] == "0/2"
    assert "dr_max_mm" not in result.stdout and "designs x" in result.stderr


def test_json_matches_the_library_and_is_alone_on_stdout(tmp_path):
    material = DEFAULT_MATERIAL.replace(w_log=0.1)
    save_material(material, tmp_path / "m.json")
    result = run("--json", "--all", "--material", str(tmp_path / "m.json"))
    assert result.exit_code == 0, result.output
    out = json.loads(result.stdout)
    lib = json_safe(sens.sensitivity(material, DESIGNS, parameters=sens.parameter_names(True)).as_dict())
    assert out["rows"] == lib["rows"] and out["derivatives"] == lib["derivatives"]
    assert out["material"]["w_log"] == 0.1 and "dr_max_mm" in out["parameters"]


def test_step_is_passed_on():
    out = json.loads(run("--json", "--step", "0.02").stdout)
    assert out["step"] == 0.02


@pytest.mark.parametrize("args, expected", [
    (["--workers", "0"], "0"), (["--step", "0"], "step"), (["--step", "nan"], "nan"),
    (["--material", "missing.json"], "missing.json"),
])
def test_bad_input_is_one_error_line_exit_2(args, expected):
    result = run(*args)
    assert result.exit_code == 2, result.output
    assert "Traceback" not in result.output
    assert len(result.stderr.splitlines()) == 1 and result.stderr.startswith("Error: ")
    assert expected in result.stderr and result.stdout == ""


def test_invalid_material_file_is_one_error_line_exit_2(tmp_path):
    path = tmp_path / "bad.json"
    path.write_text(json.dumps({**DEFAULT_MATERIAL.as_dict(), "k_r_emb": -1.0}))
    result = run("--material", str(path))
    assert result.exit_code == 2 and result.stderr.startswith("Error: ")
    assert "k_r_emb" in result.stderr and "-1.0" in result.stderr and "bad.json" in result.stderr
