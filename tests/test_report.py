"""The validation report: predictions, metrics with known values, the files, atomic writing."""
import dataclasses
import hashlib
import json
import re
import shutil

import numpy as np
import pytest

from stitchswitch.errors import InvalidInputError
from stitchswitch.reduced.model.material_io import material_hash
from stitchswitch.reduced.model.params import DEFAULT_MATERIAL, Patch
from stitchswitch.reduced.solvers import solve as solve_module
from stitchswitch.reduced.solvers.solve import DEFAULT_TOL
from stitchswitch.validation import report as report_module
from stitchswitch.validation.measured import QUANTITIES, load_measurements
from stitchswitch.validation.metrics import PAPER_TABLE1
from stitchswitch.validation.report import REPORT_FILES, predict, write_report

TRAIN = [(30.0, 0.8), (40.0, 0.9), (50.0, 0.7), (60.0, 1.0), (35.0, 0.6), (45.0, 0.85)]
VAL = [(33.0, 0.75), (42.0, 0.95), (55.0, 0.65), (58.0, 0.9)]
OFFSET = {"train": 0.5, "val": -1.0}  # measured = predicted + offset, every quantity (mm)
PNG = b"\x89PNG\r\n\x1a\n"


def model_keypoints(d, p):
    kp = solve_module.solve(Patch(d, p), DEFAULT_MATERIAL).keypoints
    return np.array([kp.h_mm, kp.r_a_mm, kp.z_a_mm, kp.r_b_mm, kp.z_b_mm])


@pytest.fixture(scope="module")
def dataset(tmp_path_factory):
    """6 train + 4 val rows made from the model's own keypoints plus a known offset."""
    lines = ["# source: synthetic (model keypoints + offset, for tests)",
             "sample_id,d_mm,fill,h_mm,r_a_mm,z_a_mm,r_b_mm,z_b_mm,split"]
    predicted = []
    for split, designs in (("train", TRAIN), ("val", VAL)):
        for k, (d, p) in enumerate(designs):
            kp = model_keypoints(d, p)
            predicted.append(kp)
            lines.append(f"{split}{k},{d!r},{p!r}," + ",".join(repr(float(v)) for v in kp + OFFSET[split])
                         + f",{split}")
    path = tmp_path_factory.mktemp("data") / "measured.csv"
    path.write_text("\n".join(lines) + "\n")
    return path, np.array(predicted)


@pytest.fixture(scope="module")
def built(dataset, tmp_path_factory):
    path, predicted = dataset
    out = tmp_path_factory.mktemp("reports") / "rep"
    rep = write_report(load_measurements(path), DEFAULT_MATERIAL, out)
    return out, rep, predicted


def expected_pct(predicted, offset):
    return 100.0 * np.mean(np.abs(offset) / np.abs(predicted + offset), axis=0)


def test_predict_matches_direct_solves(dataset):
    path, predicted = dataset
    pred = predict(load_measurements(path), DEFAULT_MATERIAL)
    assert pred.values.shape == (10, 5) and pred.all_converged
    np.testing.assert_allclose(pred.values, predicted, rtol=0, atol=1e-12)
    assert np.all(pred.residual <= DEFAULT_TOL) and len(pred.b_rule) == 10


def test_report_files_exist_and_pngs_are_valid(built):
    out, _, _ = built
    assert sorted(p.name for p in out.iterdir()) == sorted(REPORT_FILES)
    for name in REPORT_FILES:
        if name.endswith(".png"):
            data = (out / name).read_bytes()
            assert data.startswith(PNG) and b"IEND" in data[-12:]
            width, height = int.from_bytes(data[16:20], "big"), int.from_bytes(data[20:24], "big")
            assert width >= 400 and height >= 400
    assert not list(out.parent.glob(".rep.*"))  # no temporary directory left


def test_report_json_numbers_are_the_known_offsets(built, dataset):
    out, rep, predicted = built
    on_disk = json.loads((out / "report.json").read_text())
    assert on_disk == rep
    ntrain = len(TRAIN)
    for split, rows in (("train", predicted[:ntrain]), ("val", predicted[ntrain:])):
        pct = expected_pct(rows, OFFSET[split])
        for k, q in enumerate(QUANTITIES):
            m = rep[split][q]
            assert m["mae_mm"] == pytest.approx(abs(OFFSET[split]), abs=1e-9)
            assert m["pct_error"] == pytest.approx(pct[k], rel=1e-9)
            assert m["n"] == len(rows) and m["n_pct_skipped"] == 0
    path, _ = dataset
    assert rep["data"]["sha256"] == hashlib.sha256(path.read_bytes()).hexdigest()
    assert rep["data"]["synthetic"] is True and rep["data"]["n_train"] == 6
    assert rep["material"] == {"label": "default", "sha256": material_hash(DEFAULT_MATERIAL)}
    assert rep["paper_table1"]["train"] == PAPER_TABLE1["train"]
    assert rep["paper_table1"]["val"]["h"] == {"pct_error": 24.6, "mae_mm": 2.23}
    assert rep["not_converged"] == [] and rep["generator"] == "stitchswitch validate"
    assert len(rep["rows"]) == 10
    row = rep["rows"][7]
    assert (row["line"], row["sample_id"], row["split"], row["converged"]) == (10, "val1", "val", True)
    assert row["predicted"]["h"] == pytest.approx(predicted[7][0], abs=1e-12)
    assert row["measured"]["h"] == pytest.approx(predicted[7][0] - 1.0, abs=1e-12)


def test_html_is_self_contained_and_says_synthetic(built):
    out, _, _ = built
    page = (out / "report.html").read_text()
    assert page.startswith("<!DOCTYPE html>") and page.rstrip().endswith("</html>")
    for forbidden in ("http://", "https://", 'src="file', "<link", "<script", "url("):
        assert forbidden not in page
    sources = re.findall(r'<img [^>]*src="([^"]*)"', page)
    assert len(sources) == 6 and all(s.startswith("data:image/png;base64,") for s in sources)
    assert "SYNTHETIC DATA" in page and "24.6" in page
    md = (out / "report.md").read_text()
    assert "SYNTHETIC DATA" in md and "![all quantities](all_quantities.png)" in md
    assert "| h | " in md


def test_measured_source_is_reported_as_not_synthetic(dataset, tmp_path):
    path, _ = dataset
    data = dataclasses.replace(load_measurements(path), source="measured (bench, 2026)")
    rep = write_report(data, DEFAULT_MATERIAL, tmp_path / "r")
    assert rep["data"]["synthetic"] is False
    md = (tmp_path / "r" / "report.md").read_text()
    assert "does not say synthetic: measured (bench, 2026)" in md and "SYNTHETIC" not in md


def test_non_converged_solves_are_recorded(dataset, tmp_path, monkeypatch):
    real = solve_module.solve

    def flaky(patch, material, **kw):
        sol = real(patch, material, **kw)
        return dataclasses.replace(sol, converged=False) if patch.diameter_mm == 50.0 else sol

    monkeypatch.setattr(solve_module, "solve", flaky)
    path, _ = dataset
    pred = predict(load_measurements(path), DEFAULT_MATERIAL)
    assert pred.converged.tolist() == [i != 2 for i in range(10)]
    monkeypatch.setattr(report_module, "_figures", lambda *a: (_ for _ in ()).throw(RuntimeError("x")))
    with pytest.raises(RuntimeError):
        write_report(load_measurements(path), DEFAULT_MATERIAL, tmp_path / "r")
    assert list(tmp_path.iterdir()) == []


def test_failure_midway_leaves_nothing(dataset, tmp_path, monkeypatch):
    from stitchswitch.reduced.design_space import heatmap as map_plot

    def boom(*args, **kwargs):
        raise OSError(28, "No space left on device")

    monkeypatch.setattr(map_plot, "plot_height_map", boom)
    path, _ = dataset
    with pytest.raises(InvalidInputError, match="report directory .*No space left on device"):
        write_report(load_measurements(path), DEFAULT_MATERIAL, tmp_path / "r")
    assert list(tmp_path.iterdir()) == []


def test_refuses_a_foreign_directory_and_leaves_it_alone(dataset, tmp_path):
    path, _ = dataset
    out = tmp_path / "r"
    out.mkdir()
    (out / "thesis.tex").write_text("precious")
    with pytest.raises(InvalidInputError, match=r"holds 'thesis.tex', not from this tool"):
        write_report(load_measurements(path), DEFAULT_MATERIAL, out)
    assert [p.name for p in out.iterdir()] == ["thesis.tex"]
    assert sorted(p.name for p in tmp_path.iterdir()) == ["r"]
    (out / "thesis.tex").unlink()
    (out / "report.json").write_text('{"generator": "something else"}')
    with pytest.raises(InvalidInputError, match="holds no report.json of this tool"):
        write_report(load_measurements(path), DEFAULT_MATERIAL, out)
    with pytest.raises(InvalidInputError, match="parent directory .* does not exist"):
        write_report(load_measurements(path), DEFAULT_MATERIAL, tmp_path / "no" / "r")
    (tmp_path / "f").write_text("")
    with pytest.raises(InvalidInputError, match="exists and is not a directory"):
        write_report(load_measurements(path), DEFAULT_MATERIAL, tmp_path / "f")


def test_replaces_a_previous_report_and_fills_an_empty_directory(built, tmp_path, monkeypatch):
    out = tmp_path / "rep"
    shutil.copytree(built[0], out)
    rep = built[1]
    empty = tmp_path / "empty"
    empty.mkdir()
    report_module.check_report_dir(empty)  # accepted, nothing to replace
    assert report_module.check_report_dir(out) is True
    # Replace the previous report without redrawing the figures (they are tested above).
    monkeypatch.setattr(report_module, "_figures", lambda data, pred, mat, tmp: [
        (tmp / name).write_bytes(PNG) for name in report_module.FIGURES])
    (out / "report.md").write_text("stale")
    path = rep["data"]["path"]
    write_report(load_measurements(path), DEFAULT_MATERIAL, out)
    assert (out / "report.md").read_text() != "stale"
    assert sorted(p.name for p in out.iterdir()) == sorted(REPORT_FILES)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["empty", "rep"]
    write_report(load_measurements(path), DEFAULT_MATERIAL, empty)
    assert sorted(p.name for p in empty.iterdir()) == sorted(REPORT_FILES)
