"""``stitchswitch discover``: a tiny end-to-end run, the report and JSON, and input errors."""
import json

import pytest
from click.testing import CliRunner

from stitchswitch.cli.main import cli
from stitchswitch.reduced.model.material_io import save_material
from stitchswitch.validation.discovery.report import check_discovery_dir
from stitchswitch.validation.discovery.synthetic import SIGMA_MM, START_MATERIAL, TRUE_MATERIAL, dataset_text

COARSE = dict(n_nodes=80, dr_max_mm=1.0)
ARGS = ["--effects", "prestretch_loss", "--folds", "2", "--workers", "1"]


@pytest.fixture(scope="module")
def case(tmp_path_factory):
    d = tmp_path_factory.mktemp("discover")
    data = d / "data.csv"
    data.write_text(dataset_text("prestretch_loss", (0.35,), seed=21,
                                 material=TRUE_MATERIAL.replace(**COARSE),
                                 sigma_mm=tuple(0.3 * s for s in SIGMA_MM), train_d=(30.0, 70.0),
                                 train_fill=(0.7, 1.0), n_val=3))
    material = d / "start.json"
    save_material(START_MATERIAL.replace(**COARSE), material)
    return data, material


def test_report_json_and_summary(case, tmp_path):
    data, material = case
    out = tmp_path / "rep"
    js = tmp_path / "result.json"
    r = CliRunner().invoke(cli, ["discover", str(data), "--material", str(material), *ARGS,
                                 "--report", str(out), "--json", str(js)])
    assert r.exit_code == 0, r.output
    assert "SYNTHETIC" in r.stdout and "missing effect:" in r.stdout and "MAE before" in r.stdout
    assert "discovery" in r.stderr                                   # the progress bar
    rep = json.loads(js.read_text())
    for key in ("missing_effect", "ranking", "before", "after", "effect_parameters", "significant"):
        assert key in rep
    assert {"effect", "score", "val_mae_before", "val_mae_after"} <= set(rep["ranking"][0])
    assert set(rep["before"]["h"]) == {"mae_mm", "pct_error"}
    assert sorted(p.name for p in out.iterdir()) == sorted(rep["files"])
    assert (out / "report.json").read_text() == js.read_text()
    for key in ("verdict", "indistinguishable", "noise_floor", "systematic", "proposal",
                "unexplained_residual", "claims"):
        assert key in rep
    assert "noise floor (estimated)" in r.stdout and "next samples" in r.stdout
    template = (out / "next_samples.csv").read_text().splitlines()
    assert template[0].startswith("# source: TEMPLATE")
    assert len(template) == 2 + len(rep["proposal"]["designs"]) and template[2].endswith(",,,,,,train")
    html = (out / "report.html").read_text()
    assert "data:image/png;base64," in html and "Where the model is wrong" in html
    md = (out / "report.md").read_text()
    assert "## 4. The gap before and after" in md and "SYNTHETIC" in md
    # the folds whose refit kept the full fit are counted, and said where there are any
    rows = [rep["starting_model"]] + rep["ranking"]
    assert all(0 <= r["cv_stuck_folds"] <= r["cv_folds"] for r in rows)
    stuck = [r for r in rows if r["cv_stuck_folds"]]
    assert ("Stuck folds:" in md) == bool(stuck) == ("CV folds stuck)" in r.stdout)
    for row in (r for r in rep["ranking"] if r["cv_stuck_folds"]):
        assert f"{row['cv_stuck_folds']} of {row['cv_folds']} folds for {row['effect']}" in md
    # same input, same result (JSON on stdout, nothing else there); the report dir is reusable
    r2 = CliRunner().invoke(cli, ["discover", "--data", str(data), "--material", str(material),
                                  *ARGS, "--json"])
    assert r2.exit_code == 0, r2.output
    assert r2.stdout == js.read_text()
    assert "Warning: --data is deprecated; use the DATA.csv argument" in r2.stderr
    assert check_discovery_dir(out) is True


def test_relative_noise_is_passed_on_and_reported(case, tmp_path):
    data, material = case
    out = tmp_path / "rep"
    r = CliRunner().invoke(cli, ["discover", str(data), "--material", str(material), *ARGS,
                                 "--relative-noise", "--report", str(out), "--json"])
    assert r.exit_code == 0, r.output
    rep = json.loads(r.stdout)
    assert rep["config"]["relative_noise"] is True
    assert set(rep["relative_noise"]["mean_size_mm"]) == {"h", "r_a", "z_a", "r_b", "z_b"}
    assert "proportional to the size" in rep["noise_floor"]["how"]
    assert "Noise proportional to the keypoint size" in (out / "report.md").read_text()


@pytest.mark.parametrize("extra, message", [
    ([], "give the data as DATA.csv"),
    (["--demo", "x.csv"], "--demo: runs the built-in data"),
    (["x.csv", "--effects", "gravity"], "'gravity' is not in the library"),
    (["x.csv", "--effects", ","], "--effects: give at least one"),
    (["missing.csv"], "cannot be read"),
    (["x.csv", "--folds", "1"], "--folds"),
])
def test_input_errors_are_one_line(tmp_path, extra, message):
    (tmp_path / "x.csv").write_text("d_mm,fill,h_mm,r_a_mm,z_a_mm,r_b_mm,z_b_mm,split\n"
                                    "40,0.8,10,15,5,16,4,train\n50,0.8,12,17,6,18,5,val\n")
    r = CliRunner().invoke(cli, ["discover", *[str(tmp_path / e) if e.endswith(".csv") else e
                                               for e in extra]])
    assert r.exit_code == 2
    assert message in r.output and "Traceback" not in r.output
    assert len(r.output.strip().splitlines()) == 1


def test_refuses_a_foreign_report_directory_before_any_work(case, tmp_path):
    data, material = case
    out = tmp_path / "busy"
    out.mkdir()
    (out / "notes.txt").write_text("mine")
    r = CliRunner().invoke(cli, ["discover", str(data), "--material", str(material), *ARGS,
                                 "--report", str(out)])
    assert r.exit_code == 2 and "holds 'notes.txt'" in r.output
    assert (out / "notes.txt").read_text() == "mine" and len(list(out.iterdir())) == 1


@pytest.mark.slow
def test_demo_names_its_hidden_effect(tmp_path):
    """The built-in demo hides a detectable effect and the workflow names exactly it."""
    from stitchswitch.cli.validation.discover import DEMO_SOURCE

    out = tmp_path / "demo.json"
    r = CliRunner().invoke(cli, ["discover", "--demo", "--workers", "1", "--json", str(out)])
    assert r.exit_code == 0, r.output
    doc = json.loads(out.read_text())
    assert doc["verdict"] == "named"
    assert doc["missing_effect"] == DEMO_SOURCE
    assert doc["after"]["r_a"]["mae_mm"] < doc["before"]["r_a"]["mae_mm"]
    # the strength reported is the estimate refitted after the decision, and says so
    est = doc["estimate"]
    assert doc["effect_parameters"] == est["effect_parameters"]
    assert est["train_mse_mm2"] <= est["train_mse_mm2_before"]
    assert "estimate (refitted after the decision" in r.stdout
    # ... and from the starting material's own coefficients, the lower misfit kept
    prior = est["prior_start"]
    assert est["train_mse_mm2"] <= min(prior["train_mse_mm2_prior"], prior["train_mse_mm2_before"])
    assert prior["kept"] == ("prior" if prior["train_mse_mm2_prior"] < prior["train_mse_mm2_before"]
                             else "calibrated")


def test_the_report_says_when_the_estimate_came_from_the_prior_coefficients():
    from stitchswitch.validation.discovery.report import _estimate

    est = {"train_mse_mm2_before": 3.3, "train_mse_mm2": 3.1,
           "prior_start": {"kept": "prior", "train_mse_mm2_prior": 3.1,
                           "train_mse_mm2_before": 3.2}}
    assert "from the starting material's own coefficients" in _estimate({"estimate": est})
    est["prior_start"]["kept"] = "calibrated"
    assert "coefficients" not in _estimate({"estimate": est})
    assert _estimate({"estimate": None}) == ""
