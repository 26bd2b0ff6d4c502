"""Fuzzing the DXF import: line edits (group codes and values replaced, lines deleted or
repeated) and byte edits of real pattern files load or give one short error naming the file."""
import logging

from hypothesis import given

from stitchswitch.layout.garment.dxf.reader import import_dxf

from fuzzing import FUZZ, byte_edits, check_refusal, line_edits
from helpers import EXTERNAL

SEEDS = {name: (EXTERNAL / "dxf" / name).read_text(encoding="utf-8", errors="replace")
         for name in ("clo-box_R10.dxf", "ezdxf_no_layouts_R2007_SPLINE.dxf")}


def load(path):
    logging.getLogger("ezdxf").setLevel(logging.CRITICAL)
    return import_dxf(path)


@FUZZ
@given(text=line_edits(SEEDS["clo-box_R10.dxf"], separator="\n"))
def test_line_edits_of_a_clo_export(tmp_path, text):
    path = tmp_path / "pattern.dxf"
    path.write_text(text, encoding="utf-8")
    check_refusal(load, path)


@FUZZ
@given(text=line_edits(SEEDS["ezdxf_no_layouts_R2007_SPLINE.dxf"], separator="\n"))
def test_line_edits_of_splines(tmp_path, text):
    path = tmp_path / "pattern.dxf"
    path.write_text(text, encoding="utf-8")
    check_refusal(load, path)


@FUZZ
@given(data=byte_edits(SEEDS["clo-box_R10.dxf"].encode()))
def test_byte_edits(tmp_path, data):
    path = tmp_path / "pattern.dxf"
    path.write_bytes(data)
    check_refusal(load, path)
