"""Malformed DXF files: each is one ``InvalidInputError`` naming the file (and the entity or
block), never an exception of ezdxf or a recursion without end."""
import re

import ezdxf
import numpy as np
import pytest
from click.testing import CliRunner

from stitchswitch.cli.main import cli
from stitchswitch.errors import InvalidInputError
from stitchswitch.layout.garment.dxf import generic
from stitchswitch.layout.garment.dxf.reader import import_dxf


def refused(path) -> str:
    with pytest.raises(InvalidInputError) as info:
        import_dxf(path)
    message = str(info.value)
    assert str(path) in message and len(message) < 300
    return message


def mm_doc():
    doc = ezdxf.new("R2010")
    doc.header["$INSUNITS"] = 4
    return doc


def test_the_issue_reproducer_exits_2_without_output(tmp_path):
    bad = tmp_path / "x.dxf"
    bad.write_bytes(b"  0\nSECTION\n  0\nEOF\n")
    r = CliRunner().invoke(cli, ["import", str(bad), "-o", str(tmp_path / "d.json")])
    assert r.exit_code == 2 and r.output.startswith("Error: ") and r.output.count("\n") == 1
    assert "x.dxf: not a readable DXF file" in r.output and not (tmp_path / "d.json").exists()


def test_a_block_that_inserts_itself(tmp_path):
    doc = mm_doc()
    blk = doc.blocks.new("LOOP")
    blk.add_circle((0, 0), 5)
    blk.add_blockref("LOOP", (1, 0))
    doc.modelspace().add_blockref("LOOP", (0, 0))
    doc.saveas(tmp_path / "loop.dxf")
    assert "block 'LOOP' inserts itself" in refused(tmp_path / "loop.dxf")


def test_nesting_and_copies_are_bounded(tmp_path, monkeypatch):
    doc = mm_doc()
    doc.blocks.new("B0").add_circle((0, 0), 5)
    for k in range(1, 5):
        doc.blocks.new(f"B{k}").add_blockref(f"B{k - 1}", (0, 0))
    doc.modelspace().add_blockref("B4", (0, 0))
    doc.saveas(tmp_path / "deep.dxf")
    assert len(import_dxf(tmp_path / "deep.dxf")) == 1
    monkeypatch.setattr(generic, "MAX_NESTING", 3)
    assert "nested deeper than 3 levels" in refused(tmp_path / "deep.dxf")


@pytest.mark.parametrize("make, message", [
    (lambda m: m.add_circle((np.nan, 0), 5), "CIRCLE .*: centre \\(nan, 0, 0\\) is not finite"),
    (lambda m: m.add_circle((0, 0), 1e300), "radius 1e\\+300 is not in \\(0, 1e\\+06\\]"),
    (lambda m: m.add_arc((0, 0), 0, 0, 90), "radius 0 is not in"),
    (lambda m: m.add_line((0, 0), (np.inf, 1)), "LINE .*: vertex \\(inf, 1\\)"),
    (lambda m: m.add_ellipse((0, 0), (1e12, 0), 0.5), "major axis 1e\\+12"),
])
def test_bad_coordinates(tmp_path, make, message):
    doc = mm_doc()
    make(doc.modelspace())
    doc.saveas(tmp_path / "bad.dxf")
    assert re.search(message, refused(tmp_path / "bad.dxf"))


def test_a_spline_with_the_wrong_number_of_knots(tmp_path):
    doc = mm_doc()
    s = doc.modelspace().add_open_spline([(0, 0), (10, 5), (20, 0), (30, 5)], degree=3)
    s.knots = list(range(9))                        # 4 points, degree 3: 8 knots are needed
    doc.saveas(tmp_path / "knots.dxf")
    assert "malformed geometry" in refused(tmp_path / "knots.dxf")


def test_an_insert_of_a_missing_block(tmp_path, caplog):
    """Recover mode drops a reference to a missing block (and says so): nothing is left."""
    doc = mm_doc()
    doc.blocks.new("P").add_lwpolyline([(0, 0), (10, 0), (10, 10)], close=True)
    doc.modelspace().add_blockref("P", (0, 0))
    doc.saveas(tmp_path / "p.dxf")
    assert len(import_dxf(tmp_path / "p.dxf")) == 1
    text = (tmp_path / "p.dxf").read_text()
    for replacement in ("AcDbBlockReference\n  2\nQ\n", "AcDbBlockReference\n"):
        (tmp_path / "q.dxf").write_text(text.replace("AcDbBlockReference\n  2\nP\n", replacement))
        assert "no closed outline found in model space" in refused(tmp_path / "q.dxf")


def test_a_piece_name_with_a_control_character_names_the_file(tmp_path):
    """Names follow the design file's rules (no control characters, at most 100 characters),
    checked where they are read, so that the error names the DXF file."""
    doc = ezdxf.new("R12")
    blk = doc.blocks.new("FRONT_M")
    blk.add_text("Piece Name: FR\x0cONT", dxfattribs={"layer": "1"})
    blk.add_polyline2d([(0, 0), (100, 0), (100, 50), (0, 50)], close=True,
                       dxfattribs={"layer": "1"})
    doc.modelspace().add_blockref("FRONT_M", (0, 0))
    doc.modelspace().add_text("Units: METRIC")
    doc.saveas(tmp_path / "ctl.dxf")
    message = refused(tmp_path / "ctl.dxf")
    assert "piece 1 name: 'FR\\x0cONT' contains a control character (U+000C" in message
    r = CliRunner().invoke(cli, ["import", str(tmp_path / "ctl.dxf"), "-o", str(tmp_path / "d.json")])
    assert r.exit_code == 2 and "ctl.dxf: piece 1 name" in r.output
