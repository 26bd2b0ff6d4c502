"""Fuzzing the DXF import: line edits (group codes and values replaced, lines deleted or
repeated) and byte edits of real pattern files load or give one short error naming the file."""
import logging

import pytest
from hypothesis import given

from stitchswitch.layout.garment.dxf.reader import import_dxf

from fuzz_edits import byte_edit, line_edit
from fuzzing import FUZZ, check_refusal, edited
from helpers import EXTERNAL


def dxf_line_edit(rng, seed):
    return line_edit(rng, seed, separator="\n")


def load(path):
    logging.getLogger("ezdxf").setLevel(logging.CRITICAL)
    return import_dxf(path)


@pytest.mark.parametrize("name", ["clo-box_R10.dxf", "ezdxf_no_layouts_R2007_SPLINE.dxf"])
def test_corrupted_copies(tmp_path, name):
    seed = (EXTERNAL / "dxf" / name).read_bytes()

    @FUZZ
    @given(data=edited(seed, byte_edit, dxf_line_edit, dxf_line_edit))
    def check(data):
        check_refusal(load, tmp_path / "pattern.dxf", data=data)

    check()
