"""DXF import against real pattern-CAD exports (tests/data/external/dxf) and broken inputs."""

import ezdxf
import numpy as np
import pytest

from stitchswitch.errors import InvalidInputError
from stitchswitch.layout.garment.dxf.reader import import_dxf

from helpers import EXTERNAL

DXF = EXTERNAL / "dxf"
IN = 25.4


def _ring_ok(piece):
    ring = piece.outline_mm
    assert ring.ndim == 2 and ring.shape[1] == 2 and len(ring) >= 3
    assert not np.allclose(ring[0], ring[-1])               # closed ring, last point not repeated


def test_gerber_tank_28_blocks_in_inches():
    pieces = import_dxf(DXF / "WM_LOOSE_SHAPE_TANK_AAMA.DXF")
    assert pieces.style == "aama" and len(pieces) == 28
    names = {p.name for p in pieces}
    assert names == {"RELAXED TANK FR V2", "RELAXED TANK BK V2"}
    sizes = [str(s) for s in range(26, 54, 2)]
    for name in names:
        assert sorted((p.size for p in pieces if p.name == name), key=int) == sizes
    first = pieces[0]
    assert (first.name, first.size) == ("RELAXED TANK FR V2", "26")
    w, h = first.bbox_mm
    assert abs(w / IN - 27.29) < 0.01 and abs(h / IN - 10.14) < 0.01
    for p in pieces:
        _ring_ok(p)
        assert p.annotations["grain_line"].shape == (2, 2)      # layer 7 line
        assert len(p.annotations["internal_lines"]) > 0         # layer 8
    # grading: the front grows in height from size 26 to 52
    fronts = [p for p in pieces if p.name == "RELAXED TANK FR V2"]
    assert fronts[-1].bbox_mm[1] > fronts[0].bbox_mm[1]


def test_clo_pattern_nine_pieces_metric():
    pieces = import_dxf(DXF / "clo-pattern_R10.dxf")
    assert len(pieces) == 9 and {p.size for p in pieces} == {"M"}
    assert pieces[0].name == "11"
    w, h = pieces[0].bbox_mm
    assert w == pytest.approx(255.8, abs=0.1) and h == pytest.approx(703.2, abs=0.1)
    assert all(r for r in pieces.repairs)                     # recover mode fixed float-as-int codes
    for p in pieces:
        _ring_ok(p)


def test_clo_box_one_rectangle_in_inches():
    (piece,) = import_dxf(DXF / "clo-box_R10.dxf")
    assert (piece.name, piece.size) == ("Pattern2D_4937", "M")
    assert len(piece.outline_mm) == 4
    w, h = piece.bbox_mm                                      # about 118.2 x 78.8 in
    assert w == pytest.approx(118.207 * IN, abs=0.1) and h == pytest.approx(78.832 * IN, abs=0.1)


def test_r2018_lwpolylines_ellipses_circles():
    pieces = import_dxf(DXF / "ezdxf_forms_R2018_LWPOLYLINE.dxf")
    kinds = [p.name.split("_")[0] for p in pieces]
    assert pieces.style == "generic"
    assert (kinds.count("LWPOLYLINE"), kinds.count("ELLIPSE"), kinds.count("CIRCLE")) == (33, 2, 5)
    for p in pieces:
        _ring_ok(p)


def test_r2007_closed_splines_in_cm():
    pieces = import_dxf(DXF / "ezdxf_no_layouts_R2007_SPLINE.dxf")
    assert len(pieces) == 2 and all(p.name.startswith("SPLINE") for p in pieces)
    assert pieces[0].bbox_mm == pytest.approx((200.0, 200.0), abs=0.1)   # $INSUNITS = cm


def test_flattening_tolerance_on_a_circle(tmp_path):
    doc = ezdxf.new("R2010")
    doc.header["$INSUNITS"] = 4
    doc.modelspace().add_circle((0, 0), 50.0)
    doc.saveas(tmp_path / "c.dxf")
    for tol in (0.5, 0.1, 0.01):
        (p,) = import_dxf(tmp_path / "c.dxf", tolerance_mm=tol)
        r = np.hypot(*p.outline_mm.T)
        assert np.allclose(r, 50.0)
        # chord sagitta = r (1 - cos(pi / n)) <= tolerance
        assert 50.0 * (1 - np.cos(np.pi / len(r))) <= tol + 1e-9


def test_open_chains_join_and_insert_transform(tmp_path):
    doc = ezdxf.new("R2010")
    doc.header["$INSUNITS"] = 1                               # inches
    blk = doc.blocks.new("SQ")
    blk.add_line((0, 0), (2, 0))
    blk.add_lwpolyline([(2, 1), (2, 0.0002)])                # reversed, 0.005 mm gap: snapped
    blk.add_lwpolyline([(0, 0), (0, 1), (2, 1)])
    doc.modelspace().add_blockref("SQ", (10, 10), dxfattribs={"xscale": 2, "yscale": 2})
    doc.saveas(tmp_path / "sq.dxf")
    (p,) = import_dxf(tmp_path / "sq.dxf")
    assert p.bbox_mm == pytest.approx((4 * IN, 2 * IN), abs=0.01)
    assert p.outline_mm.min(axis=0) == pytest.approx((10 * IN, 10 * IN))


def _aama_with_gap(path, gap_mm):
    doc = ezdxf.new("R12")
    blk = doc.blocks.new("FRONT_M")
    blk.add_text("Piece Name: FRONT", dxfattribs={"layer": "1"})
    blk.add_text("SIZE: M", dxfattribs={"layer": "1"})
    blk.add_polyline2d([(0, 0), (100, 0), (100, 50)], dxfattribs={"layer": "1"})
    blk.add_polyline2d([(100, 50), (0, 50), (0, gap_mm)], dxfattribs={"layer": "1"})
    msp = doc.modelspace()
    msp.add_blockref("FRONT_M", (0, 0), dxfattribs={"layer": "1"})
    msp.add_text("Units: METRIC", dxfattribs={"layer": "1"})
    doc.saveas(path)


def test_aama_block_closes_within_snap(tmp_path):
    _aama_with_gap(tmp_path / "ok.dxf", 0.2)
    (p,) = import_dxf(tmp_path / "ok.dxf")
    assert (p.name, p.size, len(p.outline_mm)) == ("FRONT", "M", 4)


def test_unclosable_outline_names_block_and_gap(tmp_path):
    _aama_with_gap(tmp_path / "gap.dxf", 2.0)
    with pytest.raises(InvalidInputError, match=r"block 'FRONT_M'.*gap of 2\.000 mm"):
        import_dxf(tmp_path / "gap.dxf")


def test_unknown_units(tmp_path):
    doc = ezdxf.new("R12")
    doc.modelspace().add_circle((0, 0), 5.0)
    doc.saveas(tmp_path / "nounits.dxf")
    with pytest.raises(InvalidInputError, match="unknown units"):
        import_dxf(tmp_path / "nounits.dxf")
    (p,) = import_dxf(tmp_path / "nounits.dxf", units="cm")
    assert p.bbox_mm == pytest.approx((100.0, 100.0), abs=0.2)    # chords: 2 x tolerance


@pytest.mark.parametrize("content", [b"\x00\x01garbage\xff" * 50 + b"\nEOF\n", b""])
def test_garbage_file_names_the_file(tmp_path, content):
    bad = tmp_path / "broken.dxf"
    bad.write_bytes(content)
    with pytest.raises(InvalidInputError, match="broken.dxf"):
        import_dxf(bad)


def test_truncated_file(tmp_path):
    doc = ezdxf.new("R2010")
    doc.header["$INSUNITS"] = 4
    doc.modelspace().add_circle((0, 0), 5.0)
    doc.saveas(tmp_path / "full.dxf")
    data = (tmp_path / "full.dxf").read_bytes()
    (tmp_path / "cut.dxf").write_bytes(data[: len(data) // 2])
    with pytest.raises(InvalidInputError, match=r"cut\.dxf.*truncated"):
        import_dxf(tmp_path / "cut.dxf")
