import json

from click.testing import CliRunner

from stitchswitch.cli.main import cli
from stitchswitch.reduced.model.material_io import load_material

SMALL = """# source: synthetic (test rows from the default model)
sample_id,d_mm,fill,h_mm,r_a_mm,z_a_mm,r_b_mm,z_b_mm,split
a,40,0.8,11.73,14.60,5.79,14.68,5.70,train
b,60,0.7,14.62,20.71,6.90,20.73,6.80,train
c,50,0.9,17.33,17.20,7.10,17.30,6.90,val
"""


def test_calibrate_writes_material_and_provenance(tmp_path):
    data = tmp_path / "d.csv"
    data.write_text(SMALL)
    out = tmp_path / "m.json"
    args = ["calibrate", str(data), "--maxiter", "1", "--popsize", "2", "--workers", "1", "--out", str(out)]
    result = CliRunner().invoke(cli, args)
    assert result.exit_code == 0, result.output
    material = load_material(out)
    record = json.loads((tmp_path / "m.calibration.json").read_text())
    assert record["data"]["n_train"] == 2 and len(record["data"]["sha256"]) == 64
    assert record["data"]["source"].startswith("synthetic")
    assert record["settings"]["maxiter"] == 1 and record["fixed_parameters"] == {"k_theta_fab": 0.5}
    assert "overall scale" in record["identifiability"]["not_identifiable"]
    assert record["material"] == material.as_dict()
    # resume from the previous best
    result = CliRunner().invoke(cli, args + ["--resume"])
    assert result.exit_code == 0, result.output
    assert json.loads((tmp_path / "m.calibration.json").read_text())["settings"]["resumed"] is True


def test_calibrate_bad_input(tmp_path):
    data = tmp_path / "d.csv"
    data.write_text(SMALL.replace("0.8,11.73", "1.8,11.73"))
    out = tmp_path / "m.json"
    result = CliRunner().invoke(cli, ["calibrate", str(data), "--out", str(out)])
    assert result.exit_code == 2 and "fill" in result.output and "line 3" in result.output
    assert not out.exists()
    result = CliRunner().invoke(cli, ["calibrate", str(data), "--out", str(tmp_path / "nope" / "m.json")])
    assert result.exit_code == 2 and "does not exist" in result.output
    data.write_text(SMALL)
    result = CliRunner().invoke(cli, ["calibrate", str(data), "--out", str(out), "--resume"])
    assert result.exit_code == 2 and "no previous run" in result.output
