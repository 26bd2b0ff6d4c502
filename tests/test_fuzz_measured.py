"""Fuzzing the measured-data CSV loader: corrupted copies of the shipped SYNTHETIC file load or
give one short error naming the file."""
from importlib import resources

from hypothesis import given

from stitchswitch.validation.measured import load_measurements

from fuzz_edits import byte_edit, line_edit
from fuzzing import FUZZ, check_refusal, edited

SEED = resources.files("stitchswitch").joinpath("data/measured_synthetic.csv").read_bytes()


@FUZZ
@given(data=edited(SEED, byte_edit, line_edit, line_edit))
def test_corrupted_copies(tmp_path, data):
    check_refusal(load_measurements, tmp_path / "measured.csv", data=data)
