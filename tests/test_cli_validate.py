"""``stitchswitch validate`` through click's CliRunner."""
import json

import numpy as np
import pytest
from click.testing import CliRunner

from stitchswitch.cli.main import cli
from stitchswitch.reduced.model.material_io import default_material_path, material_hash
from stitchswitch.reduced.model.params import DEFAULT_MATERIAL, Patch
from stitchswitch.reduced.solvers.solve import solve
from stitchswitch.validation.report import REPORT_FILES

DESIGNS = {"train": [(30.0, 0.8), (40.0, 0.9), (50.0, 0.7), (60.0, 1.0), (35.0, 0.6), (45.0, 0.85)],
           "val": [(33.0, 0.75), (42.0, 0.95), (55.0, 0.65), (58.0, 0.9)]}
OFFSET = {"train": 0.5, "val": 1.0}


def run(*args):
    """Invoke the CLI; unexpected exceptions propagate (catch_exceptions=False)."""
    return CliRunner().invoke(cli, ["validate", *map(str, args)], catch_exceptions=False)


@pytest.fixture(scope="module")
def data_csv(tmp_path_factory):
    """Model keypoints plus 0.5 mm (train) or 1.0 mm (val) on every quantity."""
    lines = ["# source: measured (CLI test bench)", "d_mm,fill,h_mm,r_a_mm,z_a_mm,r_b_mm,z_b_mm,split"]
    for split, designs in DESIGNS.items():
        for d, p in designs:
            kp = solve(Patch(d, p), DEFAULT_MATERIAL).keypoints
            values = np.array([kp.h_mm, kp.r_a_mm, kp.z_a_mm, kp.r_b_mm, kp.z_b_mm]) + OFFSET[split]
            lines.append(f"{d},{p}," + ",".join(repr(float(v)) for v in values) + f",{split}")
    path = tmp_path_factory.mktemp("data") / "data.csv"
    path.write_text("\n".join(lines) + "\n")
    return path


def test_table_and_report(data_csv, tmp_path):
    out = tmp_path / "rep"
    result = run(data_csv, "--report", out)
    assert result.exit_code == 0, result.output
    assert result.stderr == ""
    lines = result.stdout.splitlines()
    assert lines[0].split() == ["quantity", "err%", "train", "err%", "val", "MAE", "train",
                                "MAE", "val", "paper", "err%", "paper", "MAE"]
    h = lines[1].split()
    assert h[0] == "h" and h[3:5] == ["0.50", "1.00"] and h[5:] == ["14.7/24.6", "1.44/2.23"]
    rows = dict(line.split(None, 1) for line in lines[7:] if line)
    assert rows["source"] == "measured (CLI test bench)"
    assert rows["solves"] == "all converged"
    assert rows["report"].startswith(str(out / "report.html"))
    assert sorted(p.name for p in out.iterdir()) == sorted(REPORT_FILES)


def test_json_equals_report_json_and_material_option(data_csv, tmp_path):
    out = tmp_path / "rep"
    result = run(data_csv, "--material", default_material_path(), "--report", out, "--json")
    assert result.exit_code == 0, result.output
    printed = json.loads(result.stdout)
    assert printed == json.loads((out / "report.json").read_text())
    assert printed["material"] == {"label": str(default_material_path()),
                                   "sha256": material_hash(DEFAULT_MATERIAL)}
    for split in ("train", "val"):
        for q in ("h", "r_a", "z_a", "r_b", "z_b"):
            assert printed[split][q]["mae_mm"] == pytest.approx(OFFSET[split], abs=1e-9)
            assert printed[split][q]["pct_error"] > 0
    assert printed["data"]["synthetic"] is False


def bad_run(tmp_path, *args):
    result = run(*args)
    assert result.exit_code == 2, result.output
    assert result.stdout == ""
    assert result.stderr.startswith("Error: ") and len(result.stderr.splitlines()) == 1
    return result.stderr


def test_bad_data_is_one_line_and_writes_nothing(data_csv, tmp_path):
    bad = tmp_path / "bad.csv"
    bad.write_text(data_csv.read_text().replace(",val\n", ",validation\n", 1))
    msg = bad_run(tmp_path, bad, "--report", tmp_path / "rep")
    assert "line 9, column split: 'validation' is not train or val" in msg
    msg = bad_run(tmp_path, tmp_path / "missing.csv", "--report", tmp_path / "rep")
    assert "cannot be read" in msg
    assert sorted(p.name for p in tmp_path.iterdir()) == ["bad.csv"]


def test_bad_options_are_one_line_and_write_nothing(data_csv, tmp_path):
    assert "Missing option '--report'" in bad_run(tmp_path, data_csv)
    material = tmp_path / "m.json"
    material.write_text("{}")
    assert "material file" in bad_run(tmp_path, data_csv, "--material", material,
                                      "--report", tmp_path / "rep")
    foreign = tmp_path / "full"
    foreign.mkdir()
    (foreign / "keep.txt").write_text("x")
    assert "not from this tool" in bad_run(tmp_path, data_csv, "--report", foreign)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["full", "m.json"]
    assert [p.name for p in foreign.iterdir()] == ["keep.txt"]
