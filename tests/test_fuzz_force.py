"""Fuzzing the switching-force CSV loader (``force --data``): corrupted copies of the shipped
SYNTHETIC table load or give one short error naming the file."""
from importlib import resources

import pytest
from hypothesis import given

from stitchswitch.reduced.design_space.force_model import load_force_csv

from fuzzing import FUZZ, byte_edits, check_refusal, line_edits

SEED = resources.files("stitchswitch").joinpath("data/force_synthetic.csv").read_bytes()


@FUZZ
@given(text=line_edits(SEED.decode("utf-8")))
def test_line_edits(tmp_path, text):
    path = tmp_path / "force.csv"
    path.write_text(text, encoding="utf-8")
    check_refusal(load_force_csv, path)


@FUZZ
@given(data=byte_edits(SEED))
def test_byte_edits(tmp_path, data):
    path = tmp_path / "force.csv"
    path.write_bytes(data)
    check_refusal(load_force_csv, path)


@pytest.mark.xfail(strict=True, reason="force_model.parse_force_csv repeats a bad split or a "
                   "repeated header cell in full ({...!r}); it should show it through "
                   "files.shown.show like every other loader")
def test_a_long_split_value_is_shortened(tmp_path):
    path = tmp_path / "force.csv"
    path.write_text("d_mm,fill,force_N,split\n40,0.8,0.5," + "x" * 10_000 + "\n")
    check_refusal(load_force_csv, path)
