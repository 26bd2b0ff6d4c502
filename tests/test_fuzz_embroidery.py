"""Fuzzing ``inspect``'s embroidery reader: byte edits of real DST, JEF, EXP and PES files
summarise or give one short error naming the file."""
import pytest
from hypothesis import given

from stitchswitch.layout.embroidery.file_summary import summarise

from fuzz_edits import byte_edit
from fuzzing import FUZZ, check_refusal, edited
from helpers import EXTERNAL


@pytest.mark.parametrize("name", ["Star.DST", "Star.JEF", "Star.EXP", "Star.pes"])
def test_corrupted_copies(tmp_path, name):
    seed = (EXTERNAL / "embroidery" / name).read_bytes()

    @FUZZ
    @given(data=edited(seed, byte_edit))
    def check(data):
        summary = check_refusal(summarise, tmp_path / name, data=data)
        if summary is not None:
            assert summary["stitches"] > 0 and summary["width_mm"] >= 0

    check()
