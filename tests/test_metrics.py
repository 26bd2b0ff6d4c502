"""Percentage error and MAE per quantity and split, against hand-computed values."""
import math

import numpy as np
import pytest

from stitchswitch.errors import InvalidInputError
from stitchswitch.validation.measured import parse_measurements
from stitchswitch.validation.metrics import (
    PAPER_TABLE1,
    mae,
    pct_error,
    quantity_metrics,
    split_metrics,
    table1,
)


def test_pct_error_and_mae_by_hand():
    measured = [10.0, 20.0, 4.0]
    predicted = [11.0, 17.0, 4.0]
    # |err| = 1, 3, 0; relative 10 %, 15 %, 0 % -> mean 25/3 %; MAE = 4/3 mm
    assert pct_error(predicted, measured) == (pytest.approx(25.0 / 3.0), 0)
    assert mae(predicted, measured) == pytest.approx(4.0 / 3.0)


def test_zero_measurements_are_skipped_in_pct_only():
    measured = [0.0, 5.0, 0.0, 10.0]
    predicted = [0.5, 6.0, 0.0, 8.0]
    pct, skipped = pct_error(predicted, measured)
    assert skipped == 2 and pct == pytest.approx((20.0 + 20.0) / 2)
    assert mae(predicted, measured) == pytest.approx((0.5 + 1.0 + 0.0 + 2.0) / 4)
    assert quantity_metrics(predicted, measured) == {
        "pct_error": pytest.approx(20.0), "mae_mm": pytest.approx(0.875), "n": 4, "n_pct_skipped": 2}
    pct, skipped = pct_error([1.0], [0.0])
    assert math.isnan(pct) and skipped == 1


def test_negative_measurements_use_the_absolute_value():
    assert pct_error([-1.5], [-2.0])[0] == pytest.approx(25.0)


def test_split_metrics_columns_are_the_quantities():
    measured = np.array([[10.0, 20.0, 5.0, 20.0, 4.0], [20.0, 10.0, 5.0, 10.0, 2.0]])
    predicted = measured + np.array([1.0, -2.0, 0.5, 0.0, 1.0])
    out = split_metrics(predicted, measured)
    assert list(out) == ["h", "r_a", "z_a", "r_b", "z_b"]
    assert out["h"]["pct_error"] == pytest.approx((10.0 + 5.0) / 2)
    assert out["r_a"]["mae_mm"] == pytest.approx(2.0)
    assert out["r_a"]["pct_error"] == pytest.approx((10.0 + 20.0) / 2)
    assert out["z_a"]["pct_error"] == pytest.approx(10.0)
    assert out["r_b"]["pct_error"] == 0.0 and out["r_b"]["mae_mm"] == 0.0
    assert out["z_b"]["pct_error"] == pytest.approx((25.0 + 50.0) / 2)
    assert all(v["n"] == 2 for v in out.values())


def test_table1_separates_train_and_val():
    text = ("d_mm,fill,h_mm,r_a_mm,z_a_mm,r_b_mm,z_b_mm,split\n"
            "40,0.8,10,10,10,10,10,train\n50,0.8,20,20,20,20,20,val\n60,0.8,10,10,10,10,10,train\n")
    data = parse_measurements(text)
    predicted = np.array([[11.0] * 5, [25.0] * 5, [12.0] * 5])
    out = table1(data, predicted)
    assert set(out) == {"train", "val"}
    assert out["train"]["h"] == {"pct_error": pytest.approx(15.0), "mae_mm": pytest.approx(1.5),
                                 "n": 2, "n_pct_skipped": 0}
    assert out["val"]["z_b"]["pct_error"] == pytest.approx(25.0)
    assert out["val"]["z_b"]["mae_mm"] == pytest.approx(5.0) and out["val"]["z_b"]["n"] == 1
    with pytest.raises(InvalidInputError, match="expected \\(3, 5\\)"):
        table1(data, predicted[:2])


def test_bad_inputs():
    with pytest.raises(InvalidInputError, match="shapes"):
        mae([1.0, 2.0], [1.0])
    with pytest.raises(InvalidInputError, match="finite"):
        pct_error([np.nan], [1.0])


def test_paper_table1_is_quoted_verbatim():
    assert PAPER_TABLE1["train"]["h"] == {"pct_error": 14.7, "mae_mm": 1.44}
    assert PAPER_TABLE1["val"]["h"] == {"pct_error": 24.6, "mae_mm": 2.23}
    assert PAPER_TABLE1["val"]["r_a"]["pct_error"] == 15.8
    assert PAPER_TABLE1["train"]["z_b"] == {"pct_error": 22.9, "mae_mm": 0.93}
    assert PAPER_TABLE1["val"]["z_a"] == {"pct_error": 31.7, "mae_mm": 1.45}
