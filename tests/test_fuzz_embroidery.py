"""Fuzzing ``inspect``'s embroidery reader: byte edits of real DST, JEF, EXP and PES files
summarise or give one short error naming the file."""
import pytest
from hypothesis import given

from stitchswitch.layout.embroidery.file_summary import summarise

from fuzzing import FUZZ, byte_edits, check_refusal
from helpers import EXTERNAL

STAR = EXTERNAL / "embroidery"


@pytest.mark.parametrize("name", ["Star.DST", "Star.JEF", "Star.EXP", "Star.pes"])
def test_byte_edits(tmp_path, name):
    seed = (STAR / name).read_bytes()

    @FUZZ
    @given(data=byte_edits(seed))
    def check(data):
        path = tmp_path / name
        path.write_bytes(data)
        summary = check_refusal(summarise, path)
        if summary is not None:
            assert summary["stitches"] > 0 and summary["width_mm"] >= 0

    check()
