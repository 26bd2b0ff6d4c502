"""Fuzzing the switching-force CSV loader (``force --data``): corrupted copies of the shipped
SYNTHETIC table load or give one short error naming the file.

A bad ``split`` cell or a repeated header cell is shown shortened (``files.shown.show``), like
every other loader's values; the line edits can put such a cell there."""
from importlib import resources

from hypothesis import given

from stitchswitch.reduced.design_space.force_model import load_force_csv

from fuzz_edits import byte_edit, line_edit
from fuzzing import FUZZ, check_refusal, edited

SEED = resources.files("stitchswitch").joinpath("data/force_synthetic.csv").read_bytes()


@FUZZ
@given(data=edited(SEED, byte_edit))
def test_byte_edits(tmp_path, data):
    check_refusal(load_force_csv, tmp_path / "force.csv", data=data)


@FUZZ
@given(data=edited(SEED, line_edit))
def test_line_edits(tmp_path, data):
    check_refusal(load_force_csv, tmp_path / "force.csv", data=data)


def test_a_long_split_value_is_shortened(tmp_path):
    path = tmp_path / "force.csv"
    path.write_text("d_mm,fill,force_N,split\n40,0.8,0.5," + "x" * 10_000 + "\n")
    check_refusal(load_force_csv, path)
