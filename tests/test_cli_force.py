"""``stitchswitch force`` through click's CliRunner."""
import json

import pytest
from click.testing import CliRunner

from stitchswitch.cli.main import cli
from stitchswitch.reduced.design_space.force_model import default_force_fit


def run(*args):
    """Invoke the CLI; unexpected exceptions propagate (catch_exceptions=False)."""
    return CliRunner().invoke(cli, ["force", *args], catch_exceptions=False)


def test_table_shows_force_scores_and_synthetic_provenance():
    result = run("--diameter", "40", "--fill", "0.8")
    assert result.exit_code == 0, result.output
    assert result.stderr == ""
    rows = dict(line.split(None, 1) for line in result.stdout.splitlines())
    expected = float(default_force_fit().model.predict(40, 0.8))
    assert rows["force"] == f"{expected:.3f} N"
    assert rows["design"] == "d = 40 mm, fill = 0.8"
    assert rows["R^2"].startswith(f"{default_force_fit().r2_train:.3f} train (25)")
    assert rows["val"].startswith("MAE")
    assert rows["data"].startswith("synthetic") and "NOT measured" in rows["data"]


def test_json_keys_and_values():
    result = run("-d", "60", "-p", "0.9", "--json")
    assert result.exit_code == 0, result.output
    data = json.loads(result.stdout)
    for key in ("force_N", "d_mm", "fill", "r2_train", "r2_val", "mae_val_N", "source"):
        assert key in data
    fit = default_force_fit()
    assert data["force_N"] == pytest.approx(float(fit.model.predict(60, 0.9)))
    assert (data["d_mm"], data["fill"], data["extrapolated"]) == (60.0, 0.9, False)
    assert data["r2_val"] == fit.r2_val and data["source"] == fit.source


def test_extrapolation_warns_but_answers():
    result = run("-d", "120", "-p", "0.8", "--json")
    assert result.exit_code == 0
    assert json.loads(result.stdout)["extrapolated"] is True
    assert result.stderr.startswith("Warning:") and "extrapolated" in result.stderr
    assert len(result.stderr.splitlines()) == 1
    assert "extrapolated" in run("-d", "50", "-p", "0.5").stderr


def test_data_option_fits_the_given_table(tmp_path):
    lines = ["# source: my bench", "d_mm,fill,force_N,split"]
    lines += [f"{d},{p},{0.01 * d * p},train" for d in (20, 50, 80) for p in (0.6, 0.8, 1.0)]
    lines += ["30,0.7,0.21,val", "70,0.9,0.63,val"]
    path = tmp_path / "f.csv"
    path.write_text("\n".join(lines) + "\n")
    data = json.loads(run("-d", "40", "-p", "0.8", "--data", str(path), "--json").stdout)
    assert data["force_N"] == pytest.approx(0.32) and data["source"] == "my bench"
    assert data["r2_train"] == pytest.approx(1.0)


@pytest.mark.parametrize("args, needle", [
    (("-d", "5", "-p", "0.8"), "5.0"),
    (("-d", "40", "-p", "1.5"), "1.5"),
    (("-d", "nan", "-p", "0.8"), "nan"),
    (("-d", "abc", "-p", "0.8"), "abc"),
    (("-d", "40"), "--fill"),
    (("-d", "40", "-p", "0.8", "--data", "missing.csv"), "missing.csv"),
])
def test_bad_input_is_one_line_exit_2(args, needle):
    result = run(*args)
    assert result.exit_code == 2
    assert result.stdout == ""
    lines = result.stderr.splitlines()
    assert len(lines) == 1 and lines[0].startswith("Error: ") and needle in lines[0]


def test_bad_data_file_names_the_line(tmp_path):
    path = tmp_path / "bad.csv"
    path.write_text("d_mm,fill,force_N,split\n40,0.8,oops,train\n")
    result = run("-d", "40", "-p", "0.8", "--data", str(path))
    assert result.exit_code == 2
    assert result.stderr.strip().splitlines() == [
        f"Error: force data {str(path)!r}, line 2, column force_N: 'oops' is not a number"]
