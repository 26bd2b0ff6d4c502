"""Fuzzing the measured-data CSV loader: corrupted copies of the shipped SYNTHETIC file load or
give one short error naming the file."""
from importlib import resources

from hypothesis import given

from stitchswitch.validation.measured import load_measurements

from fuzzing import FUZZ, byte_edits, check_refusal, line_edits

SEED = resources.files("stitchswitch").joinpath("data/measured_synthetic.csv").read_bytes()


@FUZZ
@given(text=line_edits(SEED.decode("utf-8")))
def test_line_edits(tmp_path, text):
    path = tmp_path / "measured.csv"
    path.write_text(text, encoding="utf-8")
    check_refusal(load_measurements, path)


@FUZZ
@given(data=byte_edits(SEED))
def test_byte_edits(tmp_path, data):
    path = tmp_path / "measured.csv"
    path.write_bytes(data)
    check_refusal(load_measurements, path)
