"""stitchswitch import: DXF patterns (real fixtures) and rectangles into a design file."""

import pytest
from click.testing import CliRunner

from stitchswitch.cli.main import cli
from stitchswitch.layout.garment.design_io import load_design

from helpers import EXTERNAL
from helpers import cli_run as run

DXF = EXTERNAL / "dxf"
IN = 25.4




def test_rectangle(tmp_path):
    out = tmp_path / "d.json"
    r = run("import", "--rectangle", "300x200", "-o", out)
    assert r.exit_code == 0, r.output
    assert "rectangle: 300.0 x 200.0 mm, x 0.0..300.0, y 0.0..200.0 mm, 4 points" in r.output
    d = load_design(out)
    (piece,) = d.pieces
    assert piece.name == "rectangle" and piece.outline_mm.tolist() == [[0, 0], [300, 0], [300, 200], [0, 200]]
    assert d.patches == () and piece.source == "rectangle 300x200"
    r = run("import", "--rectangle", "250 X 120", "--name", "sleeve", "-o", out)
    assert r.exit_code == 0 and load_design(out).pieces[0].name == "sleeve"


def test_gerber_tank_one_size_and_deterministic(tmp_path):
    out, again = tmp_path / "t.json", tmp_path / "t2.json"
    r = run("import", DXF / "WM_LOOSE_SHAPE_TANK_AAMA.DXF", "--size", "26", "-o", out)
    assert r.exit_code == 0, r.output
    d = load_design(out)
    assert [(p.name, p.size) for p in d.pieces] == [("RELAXED TANK FR V2", "26"),
                                                    ("RELAXED TANK BK V2", "26")]
    assert d.pieces[0].source == "WM_LOOSE_SHAPE_TANK_AAMA.DXF"
    w, h = d.pieces[0].outline_mm.max(axis=0) - d.pieces[0].outline_mm.min(axis=0)
    assert w / IN == pytest.approx(27.29, abs=0.01) and h / IN == pytest.approx(10.14, abs=0.01)
    assert run("import", DXF / "WM_LOOSE_SHAPE_TANK_AAMA.DXF", "--size", "26", "-o", again).exit_code == 0
    assert out.read_bytes() == again.read_bytes()


def test_gerber_tank_pieces_option(tmp_path):
    out = tmp_path / "t.json"
    r = run("import", DXF / "WM_LOOSE_SHAPE_TANK_AAMA.DXF", "--size", "40",
            "--pieces", "RELAXED TANK BK V2", "-o", out)
    assert r.exit_code == 0, r.output
    assert [p.name for p in load_design(out).pieces] == ["RELAXED TANK BK V2"]


@pytest.mark.parametrize("args,message", [
    ([], "the pattern has 14 sizes; choose one with --size: '26', '28'"),
    (["--size", "XL"], "size 'XL' is not in the pattern; its sizes are '26', '28'"),
    (["--size", "26", "--pieces", "SLEEVE"],
     "piece 'SLEEVE' is not in size '26' of the pattern; its pieces are 'RELAXED TANK FR V2', "
     "'RELAXED TANK BK V2'"),
])
def test_unknown_size_or_piece_lists_what_there_is(tmp_path, args, message):
    out = tmp_path / "t.json"
    r = run("import", DXF / "WM_LOOSE_SHAPE_TANK_AAMA.DXF", *args, "-o", out)
    assert r.exit_code == 2 and message in r.output and "Traceback" not in r.output
    assert not out.exists()


def test_clo_pattern_and_generic_dxf(tmp_path):
    out = tmp_path / "c.json"
    assert run("import", DXF / "clo-pattern_R10.dxf", "-o", out).exit_code == 0
    d = load_design(out)
    assert len(d.pieces) == 9 and {p.size for p in d.pieces} == {"M"}
    assert run("import", DXF / "ezdxf_no_layouts_R2007_SPLINE.dxf", "-o", out).exit_code == 0
    assert len(load_design(out).pieces) == 2       # self-touching spline outlines are kept


@pytest.mark.parametrize("args,message", [
    ([], "give either a PATTERN file or --rectangle WxH"),
    (["x.dxf", "--rectangle", "10x10"], "give either a PATTERN file or --rectangle WxH"),
    (["--rectangle", "300by200"], "--rectangle '300by200': expected WIDTHxHEIGHT"),
    (["--rectangle", "0x200"], "rectangle width 0 mm must be a positive number"),
    (["--rectangle", "10x10", "--size", "M"], "--size, --pieces and --units apply to a PATTERN"),
    (["missing.dxf"], "no such file: 'missing.dxf'"),
])
def test_bad_input(tmp_path, args, message):
    out = tmp_path / "d.json"
    r = run("import", *args, "-o", out)
    assert r.exit_code == 2 and message in r.output and "Traceback" not in r.output
    assert not out.exists()


def test_broken_dxf(tmp_path):
    bad = tmp_path / "bad.dxf"
    bad.write_text("0\nSECTION\n2\nENTITIES\n")
    out = tmp_path / "d.json"
    r = run("import", bad, "-o", out)
    assert r.exit_code == 2 and "truncated DXF file" in r.output and not out.exists()


def test_import_names_the_frame_and_warns_on_implausible_sizes(tmp_path):
    from pathlib import Path
    tank = Path(__file__).parent / "data/external/dxf/WM_LOOSE_SHAPE_TANK_AAMA.DXF"
    args = ["import", str(tank), "--size", "36", "--pieces", "RELAXED TANK FR V2"]
    r = CliRunner().invoke(cli, [*args, "-o", str(tmp_path / "a.json")])
    assert r.exit_code == 0 and "Warning" not in r.output
    assert "678.4 x 290.5 mm, x 7.8..686.2, y 503.9..794.3 mm" in r.output
    r = CliRunner().invoke(cli, [*args, "--units", "mm", "-o", str(tmp_path / "b.json")])
    assert r.exit_code == 0
    assert "Warning: piece RELAXED TANK FR V2 is 26.7 x 11.4 mm, implausibly small" in r.stderr
    assert "25.4 times this is 678 mm" in r.stderr
