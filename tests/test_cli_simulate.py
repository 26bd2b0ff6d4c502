"""``stitchswitch simulate`` through click's CliRunner."""
import json
import os

import numpy as np
import pytest
from click.testing import CliRunner

from stitchswitch.cli.main import cli
from stitchswitch.reduced.model.material_io import save_material
from stitchswitch.reduced.model.params import DEFAULT_MATERIAL

KEYS = ("h_mm", "r_a_mm", "z_a_mm", "r_b_mm", "z_b_mm", "energy", "residual", "converged",
        "iterations", "solve_s")


def run(*args):
    """Invoke the CLI; unexpected exceptions propagate (catch_exceptions=False)."""
    return CliRunner().invoke(cli, ["simulate", *args], catch_exceptions=False)


def test_default_run_prints_the_table():
    result = run()
    assert result.exit_code == 0, result.output
    assert result.stderr == ""
    names = [line.split("  ")[0].strip() for line in result.stdout.splitlines()]
    for name in ("h", "r_a", "z_a", "r_b", "z_b", "energy", "residual", "converged",
                 "iterations", "solve time"):
        assert name in names
    assert "d = 40 mm, fill = 0.8" in result.stdout
    assert "converged   yes" in result.stdout


def test_json():
    result = run("--json", "--diameter", "60", "--fill", "0.5")
    assert result.exit_code == 0, result.output
    data = json.loads(result.stdout)
    assert set(KEYS) <= set(data)
    assert data["d_mm"] == 60.0 and data["fill"] == 0.5 and data["solver"] == "newton"
    assert data["converged"] is True and data["h_mm"] > 0


def test_material_file_is_used(tmp_path):
    save_material(DEFAULT_MATERIAL.replace(w_log=0.2), tmp_path / "m.json")
    default = json.loads(run("--json").stdout)
    other = json.loads(run("--json", "--material", str(tmp_path / "m.json")).stdout)
    assert other["energy"] != default["energy"]


def test_profile_csv(tmp_path):
    path = tmp_path / "profile.csv"
    result = run("--json", "--profile-csv", str(path))
    assert result.exit_code == 0, result.output
    lines = path.read_text().splitlines()
    assert lines[0] == "# stitchswitch profile, d_mm=40.0, fill=0.8, solver=newton"
    assert lines[1] == "R_mm,r_mm,z_mm"
    table = np.loadtxt(path, delimiter=",", skiprows=2)
    assert table.shape == (300, 3) and np.isfinite(table).all()
    named = np.genfromtxt(path, delimiter=",", skip_header=1, names=True)
    assert named.dtype.names == ("R_mm", "r_mm", "z_mm")
    assert np.isclose(named["z_mm"].max() - named["z_mm"].min(), json.loads(result.stdout)["h_mm"])
    assert os.listdir(tmp_path) == ["profile.csv"]


def test_verbosity_flags():
    quiet = CliRunner().invoke(cli, ["-q", "simulate", "--solver", "adam", "--max-iter", "50"],
                               catch_exceptions=False)
    assert quiet.exit_code == 0 and quiet.stderr == ""
    verbose = CliRunner().invoke(cli, ["-v", "simulate"], catch_exceptions=False)
    assert verbose.exit_code == 0 and "Info: solving d = 40 mm" in verbose.stderr


def test_version():
    result = CliRunner().invoke(cli, ["--version"])
    assert result.exit_code == 0 and "0.1.0" in result.output


def test_adam_not_converged_still_reports(tmp_path):
    path = tmp_path / "adam.csv"
    result = run("--solver", "adam", "--max-iter", "50", "--json", "--profile-csv", str(path))
    assert result.exit_code == 0, result.output
    data = json.loads(result.stdout)
    assert data["converged"] is False and data["solver"] == "adam" and data["iterations"] == 50
    warning = result.stderr.strip().splitlines()
    assert len(warning) == 1 and warning[0].startswith("Warning: the adam solve did not converge")
    assert np.loadtxt(path, delimiter=",", skiprows=2).shape == (300, 3)


BAD = [
    (["--diameter", "0"], "0.0"),
    (["--diameter", "-5"], "-5.0"),
    (["--diameter=-5"], "-5.0"),
    (["--diameter", "5"], "5.0"),
    (["--diameter", "200"], "200.0"),
    (["--diameter", "nan"], "'nan'"),
    (["--diameter", "inf"], "'inf'"),
    (["--diameter", "forty"], "'forty'"),
    (["--fill", "0"], "fill: 0.0"),
    (["--fill", "1.5"], "fill: 1.5"),
    (["--fill", "-0.1"], "fill: -0.1"),
    (["--fill", "nan"], "'nan'"),
    (["--solver", "lbfgs"], "'lbfgs'"),
    (["--max-iter", "0"], "--max-iter"),
]


def assert_one_line_error(result, expected, tmp_path):
    assert result.exit_code == 2, result.output
    assert result.stdout == ""
    lines = result.stderr.splitlines()
    assert len(lines) == 1, result.stderr
    assert lines[0].startswith("Error: ") and expected in lines[0]
    assert "Traceback" not in result.output
    assert not (tmp_path / "out.csv").exists()
    assert [p for p in os.listdir(tmp_path) if p != "m.json"] == []


@pytest.mark.parametrize("args, expected", BAD, ids=[" ".join(a) for a, _ in BAD])
def test_bad_input_is_one_line_exit_2(tmp_path, args, expected):
    result = run(*args, "--profile-csv", str(tmp_path / "out.csv"))
    assert_one_line_error(result, expected, tmp_path)


@pytest.mark.parametrize("content, expected", [
    (None, "cannot be read"),
    ("{not json", "not valid JSON (Expecting property name enclosed in double quotes at line 1"),
    ('{"w_log": 1.0}', "$.w_b_emb: missing (also missing: 'w_b_fab'"),
    (json.dumps({**DEFAULT_MATERIAL.as_dict(), "colour": 3}), "$.colour: unknown key (allowed: "),
    (json.dumps({**DEFAULT_MATERIAL.as_dict(), "eta": 0.5}), "$.eta: 0.5"),
])
def test_bad_material_file_is_one_line_exit_2(tmp_path, content, expected):
    path = tmp_path / "m.json"
    if content is not None:
        path.write_text(content)
    result = run("--material", str(path), "--profile-csv", str(tmp_path / "out.csv"))
    assert_one_line_error(result, expected, tmp_path)
    assert str(path) in result.stderr


def test_unwritable_profile_path_is_one_line(tmp_path):
    result = run("--profile-csv", str(tmp_path / "missing-dir" / "out.csv"))
    assert result.exit_code == 2
    assert len(result.stderr.splitlines()) == 1 and result.stderr.startswith("Error: ")
    assert "missing-dir" in result.stderr and "Traceback" not in result.output
    assert os.listdir(tmp_path) == []
