import json
import os
import signal
import subprocess
import sys
import time

import pytest
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
    args = ["calibrate", str(data), "--maxiter", "1", "--popsize", "2", "--workers", "1", "-o", str(out)]
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
    result = CliRunner().invoke(cli, ["calibrate", str(data), "-o", str(out)])
    assert result.exit_code == 2 and "fill" in result.output and "line 3" in result.output
    assert not out.exists()
    result = CliRunner().invoke(cli, ["calibrate", str(data), "-o", str(tmp_path / "nope" / "m.json")])
    assert result.exit_code == 2 and "does not exist" in result.output
    data.write_text(SMALL)
    result = CliRunner().invoke(cli, ["calibrate", str(data), "-o", str(out), "--resume"])
    assert result.exit_code == 2 and "no previous run" in result.output


def _setup(tmp_path):
    data = tmp_path / "d.csv"
    data.write_text(SMALL)
    return data, tmp_path / "m.json"


@pytest.mark.parametrize("content, needle", [
    ("", "not valid JSON"),
    ("{not json", "not valid JSON"),
    ("[1, 2]", "must be a calibration record (a JSON object), got an array"),
    ('{"material": {}}', "$.data: missing"),
    ('{"data": {"sha256": "x"}}', "$.material: missing"),
    ('{"material": {}, "data": {"sha256": "0123456789abcdef"}}', "fitted to other data"),
    ('{"material": {}, "data": {}}', "$.data.sha256: missing"),
    ('{"material": 5, "data": {"sha256": "SHA"}}', "$.material"),
    ('{"material": {"w_b_emb": -1}, "data": {"sha256": "SHA"}}', "$.material"),
])
@pytest.mark.parametrize("sidecar", ["checkpoint", "calibration"])
def test_resume_from_a_bad_sidecar_is_one_error(tmp_path, content, needle, sidecar):
    from stitchswitch.validation.measured import load_measurements

    data, out = _setup(tmp_path)
    path = tmp_path / f"m.{sidecar}.json"
    path.write_text(content.replace("SHA", load_measurements(data).sha256))
    result = CliRunner().invoke(cli, ["calibrate", str(data), "-o", str(out), "--resume"])
    assert result.exit_code == 2, result.output
    (line,) = result.stderr.splitlines()
    assert line.startswith("Error: --resume: calibration record") and str(path) in line
    assert needle in line and len(line) < 400
    assert "Traceback" not in result.output and not out.exists()


def test_calibrate_checkpoints_each_generation_and_writes_out_at_the_end(tmp_path, monkeypatch):
    from stitchswitch.cli.model import calibrate as cmd

    data, out = _setup(tmp_path)
    out.write_text("previous material\n")
    seen = []
    real = cmd.atomic_write_text

    def spy(path, text):
        seen.append((os.path.basename(path), out.read_text()))
        return real(path, text)
    monkeypatch.setattr(cmd, "atomic_write_text", spy)
    result = CliRunner().invoke(cli, ["calibrate", str(data), "--maxiter", "2", "--popsize", "2",
                                      "--workers", "1", "-o", str(out)])
    assert result.exit_code == 0, result.output
    checkpoints = [s for s in seen if s[0] == "m.checkpoint.json"]
    assert len(checkpoints) >= 2 and all(s[1] == "previous material\n" for s in checkpoints)
    assert load_material(out) is not None
    assert not (tmp_path / "m.checkpoint.json").exists()           # removed when finished
    assert sorted(os.listdir(tmp_path)) == ["d.csv", "m.calibration.json", "m.json"]


def test_a_killed_calibration_leaves_the_previous_material_and_can_resume(tmp_path):
    data, out = _setup(tmp_path)
    out.write_text('{"previous": true}\n')
    checkpoint = tmp_path / "m.checkpoint.json"
    env = {**os.environ, "PYTHONPATH": os.pathsep.join(sys.path)}
    proc = subprocess.Popen([sys.executable, "-m", "stitchswitch", "calibrate", str(data),
                             "--maxiter", "200", "--popsize", "2", "--workers", "1",
                             "-o", str(out)], env=env, stdout=subprocess.DEVNULL,
                            stderr=subprocess.DEVNULL)
    try:
        deadline = time.monotonic() + 120
        while not checkpoint.exists() and time.monotonic() < deadline and proc.poll() is None:
            time.sleep(0.05)
        assert checkpoint.exists(), "no checkpoint was written"
        time.sleep(0.3)
    finally:
        proc.send_signal(signal.SIGKILL)
        proc.wait()
    assert proc.returncode == -signal.SIGKILL
    assert out.read_text() == '{"previous": true}\n'
    record = json.loads(checkpoint.read_text())
    assert record["message"] == "in progress" and record["generations"] >= 1
    result = CliRunner().invoke(cli, ["calibrate", str(data), "--maxiter", "1", "--popsize", "2",
                                      "--workers", "1", "-o", str(out), "--resume"])
    assert result.exit_code == 0, result.output
    provenance = json.loads((tmp_path / "m.calibration.json").read_text())
    assert provenance["start_material"] == f"resumed from {checkpoint}"
    assert load_material(out) is not None and not checkpoint.exists()
    assert not [n for n in os.listdir(tmp_path) if n.startswith(".")]
