"""The switching-force polynomial (paper, Appendix B), its CSV format and the synthetic data."""
import pathlib
import subprocess
import sys

import numpy as np
import pytest

from stitchswitch.errors import InvalidInputError
from stitchswitch.reduced.design_space.force_model import (
    ForceModel,
    ForceSample,
    default_force_csv_path,
    default_force_fit,
    fit_force_model,
    load_force_csv,
    parse_force_csv,
)

ROOT = pathlib.Path(__file__).resolve().parent.parent
SCRIPT = ROOT / "scripts" / "make_force_dataset.py"
TRAIN_D = (20.0, 40.0, 60.0, 70.0, 90.0)
TRAIN_P = (0.6, 0.7, 0.8, 0.9, 1.0)
HEADER = "sample_id,d_mm,fill,force_N,split\n"


def grid_rows(model, split="train", ds=TRAIN_D, ps=TRAIN_P):
    return [ForceSample(d, p, float(model.predict(d, p)), split) for p in ps for d in ds]


def test_recovers_known_coefficients_from_noise_free_quadratic():
    true = ForceModel(0.05, -0.002, 0.1, 3e-5, 0.2, 0.006)
    rows = grid_rows(true) + grid_rows(true, "val", ds=(25.0, 55.0, 85.0), ps=(0.65, 0.95))
    fit = fit_force_model(rows, "test")
    np.testing.assert_allclose(fit.model.coefficients, true.coefficients, rtol=1e-9, atol=1e-12)
    assert fit.r2_train == pytest.approx(1.0, abs=1e-12) and fit.r2_val == pytest.approx(1.0, abs=1e-12)
    assert fit.mae_train_N < 1e-12 and fit.mae_val_N < 1e-12
    assert (fit.n_train, fit.n_val, fit.source) == (25, 6, "test")
    assert fit.d_range_mm == (20.0, 90.0) and fit.fill_range == (0.6, 1.0)


def test_predict_is_vectorized_and_as_dict_round_trips():
    m = ForceModel(1.0, 2.0, 3.0, 4.0, 5.0, 6.0)
    d, p = np.array([[1.0], [2.0]]), np.array([0.5, 1.0, 0.0])
    assert m.predict(d, p).shape == (2, 3)
    assert m.predict(2.0, 0.5) == pytest.approx(1 + 4 + 1.5 + 16 + 1.25 + 6)
    assert ForceModel(**m.as_dict()) == m


def test_r2_and_mae_match_hand_computation():
    # Train: the 3 x 3 grid d in {20, 40, 60}, p in {0.6, 0.8, 1.0}: 9 rows, 6 unknowns, so the
    # fit is not exact. The hand computation uses the model the fit returns.
    rng = np.random.default_rng(0)
    train = [ForceSample(d, p, float(f), "train")
             for (d, p), f in zip([(d, p) for d in (20.0, 40.0, 60.0) for p in (0.6, 0.8, 1.0)],
                                  rng.uniform(0.1, 0.5, 9))]
    val = [ForceSample(30.0, 0.7, 0.2, "val"), ForceSample(50.0, 0.9, 0.4, "val"),
           ForceSample(45.0, 0.65, 0.1, "val")]
    fit = fit_force_model(train + val)
    pred = [float(fit.model.predict(r.diameter_mm, r.fill)) for r in val]
    y = [0.2, 0.4, 0.1]
    mean = sum(y) / 3
    ss_res = sum((a - b) ** 2 for a, b in zip(y, pred))
    ss_tot = sum((a - mean) ** 2 for a in y)
    assert fit.r2_val == pytest.approx(1 - ss_res / ss_tot, rel=1e-12)
    assert fit.mae_val_N == pytest.approx(sum(abs(a - b) for a, b in zip(y, pred)) / 3, rel=1e-12)
    yt = [r.force_N for r in train]
    pt = [float(fit.model.predict(r.diameter_mm, r.fill)) for r in train]
    mt = sum(yt) / 9
    assert fit.r2_train == pytest.approx(
        1 - sum((a - b) ** 2 for a, b in zip(yt, pt)) / sum((a - mt) ** 2 for a in yt), rel=1e-12)
    # least squares: the train residual is orthogonal to every feature, e.g. sums to zero
    assert sum(a - b for a, b in zip(yt, pt)) == pytest.approx(0.0, abs=1e-12)


def test_fit_rejects_too_few_rows_an_empty_split_and_a_degenerate_design():
    m = ForceModel(0.0, 0.001, 0.1, 0.0, 0.0, 0.0)
    val = [ForceSample(50.0, 0.8, 0.2, "val")]
    with pytest.raises(InvalidInputError, match="5 train rows, need at least 6"):
        fit_force_model(grid_rows(m)[:5] + val)
    with pytest.raises(InvalidInputError, match="the val split is empty"):
        fit_force_model(grid_rows(m))
    with pytest.raises(InvalidInputError, match="the train split is empty"):
        fit_force_model(val)
    with pytest.raises(InvalidInputError, match="determine only"):   # two fill values: p^2 ~ p
        fit_force_model(grid_rows(m, ps=(0.6, 1.0)) + val)


def test_shipped_dataset_is_labelled_synthetic_and_has_the_papers_design():
    first = default_force_csv_path().read_text("utf-8").splitlines()[0]
    assert first.startswith("# source: synthetic") and first.endswith("NOT measured")
    rows, source = load_force_csv(str(default_force_csv_path()))
    assert source.startswith("synthetic") and "NOT measured" in source
    train = [r for r in rows if r.split == "train"]
    val = [r for r in rows if r.split == "val"]
    assert sorted((r.diameter_mm, r.fill) for r in train) == sorted((d, p) for d in TRAIN_D for p in TRAIN_P)
    assert len(val) == 28 and all(20 <= r.diameter_mm <= 90 and 0.6 <= r.fill <= 1.0 for r in val)
    f = np.array([r.force_N for r in train])
    assert 0.0 < f.min() < 0.1 and 0.65 < f.max() < 0.9       # paper: 0.04-0.77 N


def test_shipped_forces_increase_with_d_and_p():
    rows, _ = load_force_csv(str(default_force_csv_path()))
    train = np.array([(r.diameter_mm, r.fill, r.force_N) for r in rows if r.split == "train"])
    for col, levels in ((0, TRAIN_D), (1, TRAIN_P)):
        means = [train[train[:, col] == v, 2].mean() for v in levels]
        assert np.all(np.diff(means) > 0)
    model = default_force_fit().model
    d, p = np.meshgrid(np.linspace(20, 90, 71), np.linspace(0.6, 1.0, 41))
    F = model.predict(d, p)
    assert np.all(np.diff(F, axis=1) > 0)                      # increasing in d everywhere
    assert np.all(np.diff(F[:, d[0] >= 25], axis=0) > 0)       # in p except the d ~ 20 corner
    assert np.diff(F, axis=0).min() > -1e-4                    # where it dips by < 0.1 mN
    assert model.c_dp > 0                                       # the d x p interaction


def test_default_fit_is_near_the_papers_figures():
    fit = default_force_fit()
    assert fit is default_force_fit()
    assert (fit.n_train, fit.n_val) == (25, 28)
    assert 0.9 <= fit.r2_train <= 0.97 and 0.75 <= fit.r2_val <= 0.9    # paper: 0.95 / 0.80
    assert 0.02 <= fit.mae_val_N <= 0.08                                 # paper: 0.06 N
    assert fit.source.startswith("synthetic")


def test_generator_reproduces_the_shipped_file(tmp_path):
    out = tmp_path / "force.csv"
    subprocess.run([sys.executable, str(SCRIPT), str(out)], check=True)
    assert out.read_bytes() == default_force_csv_path().read_bytes()


def write(tmp_path, text):
    path = tmp_path / "f.csv"
    path.write_text(text)
    return path


def test_csv_comments_extra_columns_and_provenance(tmp_path):
    text = ("# a comment\n# source: bench test, 2024\n# source: not this one\n"
            "notes,split,force_N,fill,d_mm,sample_id\n\n"
            '"long, quoted",train,0.25,0.8,40,A1\n  # interleaved comment\nx,val,0.3,0.9,50,A2\n')
    rows, source = load_force_csv(write(tmp_path, text))
    assert source == "bench test, 2024"
    assert rows == [ForceSample(40.0, 0.8, 0.25, "train", "A1"),
                    ForceSample(50.0, 0.9, 0.3, "val", "A2")]
    _, source = parse_force_csv(HEADER + "a,40,0.8,0.2,train\n", "x.csv")
    assert source.startswith("unspecified")


@pytest.mark.parametrize("text, message", [
    ("d_mm,fill,split\n40,0.8,train\n", "line 1: header has no column 'force_N'"),
    ("# c\nd_mm,fill,force_N,split,fill\n", "line 2: column 'fill' appears twice"),
    (HEADER + "a,40,0.8,0.2,train\nb,40,0.8,abc,train\n", "line 3, column force_N: 'abc' is not a number"),
    (HEADER + "a,nan,0.8,0.2,train\n", "line 2, column d_mm: 'nan' is not a finite number"),
    (HEADER + "a,40,inf,0.2,train\n", "line 2, column fill: 'inf' is not a finite number"),
    (HEADER + "a,200,0.8,0.2,train\n", "line 2, column d_mm: 200 is outside [10, 150] mm"),
    (HEADER + "a,5,0.8,0.2,train\n", "line 2, column d_mm: 5 is outside"),
    (HEADER + "a,40,0,0.2,train\n", "line 2, column fill: 0 is outside (0, 1]"),
    (HEADER + "a,40,1.2,0.2,train\n", "line 2, column fill: 1.2 is outside (0, 1]"),
    (HEADER + "a,40,0.8,-0.1,train\n", "line 2, column force_N: -0.1 is negative"),
    (HEADER + "a,40,0.8,0.1,test\n", "line 2, column split: 'test' is not train or val"),
    (HEADER + "\n# x\na,40,0.8,0.1\n", "line 4: 4 fields, the header has 5"),
    ("# only comments\n", "no header"),
    (HEADER, "no data rows"),
])
def test_csv_errors_name_line_and_column(tmp_path, text, message):
    path = write(tmp_path, text)
    with pytest.raises(InvalidInputError) as err:
        load_force_csv(path)
    assert message in str(err.value) and str(path) in str(err.value)
    assert "\n" not in str(err.value)


def test_unreadable_file(tmp_path):
    with pytest.raises(InvalidInputError, match="cannot be read"):
        load_force_csv(tmp_path / "missing.csv")
