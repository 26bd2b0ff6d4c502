"""The measured-data CSV format: a valid file, every rejected input with its line and column."""
import hashlib

import numpy as np
import pytest

from stitchswitch.errors import InvalidInputError
from stitchswitch.validation.measured import (
    QUANTITIES,
    MeasuredData,
    Measurement,
    load_measurements,
    parse_measurements,
)

HEADER = "sample_id,d_mm,fill,h_mm,r_a_mm,z_a_mm,r_b_mm,z_b_mm,split,force_N,notes"
ROWS = ["A1,40,0.8,11.7,14.6,5.8,14.7,5.7,train,0.21,first",
        "A2,60,1.0,17.3,21.2,7.7,21.2,7.4,train,,\"photo 2, left\"",
        "B1,50,0.7,14.8,18.0,6.9,18.1,6.7,val,0.3,"]
VALID = "\n".join(["# source: measured (bench photos, 2026-01)", "# second comment", HEADER,
                   "", *ROWS]) + "\n"


def text_with(row: str, header: str = HEADER, extra=()) -> str:
    """A file whose data row ``row`` is on line 3, followed by ROWS[1:] and ``extra``."""
    return "\n".join(["# source: test", header, row, *ROWS[1:], *extra]) + "\n"


def error(text: str) -> str:
    with pytest.raises(InvalidInputError) as exc:
        parse_measurements(text, "'m.csv'")
    msg = str(exc.value)
    assert "\n" not in msg and msg.startswith("measured data 'm.csv'")
    return msg


def test_valid_file_rows_arrays_and_provenance():
    data = parse_measurements(VALID, "'m.csv'")
    assert data.source == "measured (bench photos, 2026-01)" and not data.synthetic
    assert len(data.rows) == 3 and [r.line for r in data.rows] == [5, 6, 7]
    first = data.rows[0]
    assert first == Measurement(40.0, 0.8, 11.7, 14.6, 5.8, 14.7, 5.7, "train", "A1", 0.21,
                                "first", 5)
    assert data.rows[1].force_N is None and data.rows[1].notes == "photo 2, left"
    assert [r.sample_id for r in data.split("train")] == ["A1", "A2"]
    assert [r.sample_id for r in data.split("val")] == ["B1"]
    np.testing.assert_array_equal(data.array("diameter_mm"), [40, 60, 50])
    np.testing.assert_array_equal(data.array("h", "val"), [14.8])
    np.testing.assert_array_equal(data.array("force_N"), [0.21, np.nan, 0.3])
    kp = data.keypoints("train")
    assert kp.shape == (2, 5) and QUANTITIES == ("h", "r_a", "z_a", "r_b", "z_b")
    np.testing.assert_array_equal(kp[0], [11.7, 14.6, 5.8, 14.7, 5.7])
    assert data.keypoints().shape == (3, 5)
    assert data.sha256 == hashlib.sha256(VALID.encode()).hexdigest()


def test_minimal_columns_any_order_and_no_source():
    text = "split,z_b_mm,r_b_mm,z_a_mm,r_a_mm,h_mm,fill,d_mm\ntrain,1,2,3,4,5,0.5,20\nval,0,2,0,4,0,1,150\n"
    data = parse_measurements(text)
    assert data.source == "unspecified" and not data.synthetic
    assert data.rows[0].h_mm == 5 and data.rows[0].diameter_mm == 20 and data.rows[0].sample_id == ""
    assert data.rows[1].label == "line 3"


def test_synthetic_source_is_recognized():
    data = parse_measurements(VALID.replace("measured (bench", "synthetic (made up"))
    assert data.synthetic and data.source.startswith("synthetic")


def test_load_hashes_the_file_bytes_and_keeps_the_path(tmp_path):
    path = tmp_path / "m.csv"
    raw = b"\xef\xbb\xbf" + VALID.encode()  # a byte-order mark is dropped but hashed
    path.write_bytes(raw)
    data = load_measurements(path)
    assert isinstance(data, MeasuredData) and data.path == str(path)
    assert data.sha256 == hashlib.sha256(raw).hexdigest()
    assert data.rows == parse_measurements(VALID).rows


def test_unreadable_and_non_utf8_files(tmp_path):
    with pytest.raises(InvalidInputError, match=r"measured data .*nope.csv.*cannot be read"):
        load_measurements(tmp_path / "nope.csv")
    bad = tmp_path / "bad.csv"
    bad.write_bytes(b"d_mm\xff\n")
    with pytest.raises(InvalidInputError, match="is not UTF-8"):
        load_measurements(bad)


@pytest.mark.parametrize("header, expected", [
    (HEADER.replace("h_mm,", ""), "line 2, column h_mm: the header has no column 'h_mm'"),
    (HEADER + ",colour", "line 2, column 12: unknown column 'colour'"),
    (HEADER + ",notes", "line 2, column 12: column 'notes' appears twice"),
])
def test_header_errors(header, expected):
    assert expected in error(text_with(ROWS[0], header=header))


@pytest.mark.parametrize("row, expected", [
    ("A1,40,0.8,abc,14.6,5.8,14.7,5.7,train,,", "line 3, column h_mm: 'abc' is not a number"),
    ("A1,40,0.8,11.7,,5.8,14.7,5.7,train,,", "line 3, column r_a_mm: the value is empty"),
    ("A1,40,0.8,11.7,14.6,nan,14.7,5.7,train,,", "line 3, column z_a_mm: 'nan' is not a finite"),
    ("A1,40,0.8,11.7,14.6,5.8,inf,5.7,train,,", "line 3, column r_b_mm: 'inf' is not a finite"),
    ("A1,9,0.8,11.7,14.6,5.8,14.7,5.7,train,,", "line 3, column d_mm: 9 is outside [10, 150] mm"),
    ("A1,151,0.8,11.7,14.6,5.8,14.7,5.7,train,,", "column d_mm: 151 is outside [10, 150] mm"),
    ("A1,40,0,11.7,14.6,5.8,14.7,5.7,train,,", "line 3, column fill: 0 is outside (0, 1]"),
    ("A1,40,1.01,11.7,14.6,5.8,14.7,5.7,train,,", "column fill: 1.01 is outside (0, 1]"),
    ("A1,40,0.8,-1,14.6,5.8,14.7,5.7,train,,", "line 3, column h_mm: -1 is outside [0, 200) mm"),
    ("A1,40,0.8,11.7,14.6,200,14.7,5.7,train,,", "column z_a_mm: 200 is outside [0, 200) mm"),
    ("A1,40,0.8,11.7,14.6,5.8,14.7,-0.5,train,,", "column z_b_mm: -0.5 is outside [0, 200) mm"),
    ("A1,40,0.8,11.7,0,5.8,14.7,5.7,train,,", "line 3, column r_a_mm: 0 is outside (0, 200) mm"),
    ("A1,40,0.8,11.7,14.6,5.8,250,5.7,train,,", "column r_b_mm: 250 is outside (0, 200) mm"),
    ("A1,40,0.8,11.7,14.6,5.8,14.7,5.7,train,-0.1,", "line 3, column force_N: -0.1 is negative"),
    ("A1,40,0.8,11.7,14.6,5.8,14.7,5.7,test,,", "line 3, column split: 'test' is not train or val"),
    ("A1,40,0.8,11.7,14.6,5.8,14.7,5.7,,,", "line 3, column split: '' is not train or val"),
    ("A1,40,0.8,11.7,14.6,5.8,14.7,5.7,train,", "line 3, column 11 (notes): missing; the row has 10"),
    ("A1,40,0.8,11.7,14.6,5.8,14.7,5.7,train,,,x", "line 3, column 12: beyond the header"),
])
def test_row_errors_name_line_and_column(row, expected):
    assert expected in error(text_with(row))


def test_duplicate_sample_id_names_both_lines():
    msg = error(text_with(ROWS[0], extra=["A1,70,0.9,1,2,3,4,5,val,,"]))
    assert "line 6, column sample_id: 'A1' is also the sample id on line 3" in msg


def test_empty_sample_ids_are_not_duplicates():
    rows = [r.replace("A1", "").replace("A2", "") for r in ROWS]
    assert len(parse_measurements("\n".join([HEADER, *rows])).rows) == 3


@pytest.mark.parametrize("split", ["train", "val"])
def test_an_empty_split_is_rejected(split):
    other = "val" if split == "train" else "train"
    rows = [r.replace(f",{split},", f",{other},") for r in ROWS]
    msg = error("\n".join(["# x", HEADER, *rows]))
    assert f"line 2, column split: the {split} split is empty" in msg


def test_no_header():
    assert "no header line" in error("# source: nothing\n\n")


def test_split_and_array_reject_unknown_names():
    data = parse_measurements(VALID)
    with pytest.raises(InvalidInputError, match="'test' is not train or val"):
        data.split("test")
    with pytest.raises(InvalidInputError, match="'notes' is not one of"):
        data.array("notes")
