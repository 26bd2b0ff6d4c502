"""stitchswitch place: at a point, on a grid, along a polyline; in place or to -o; errors."""
import pytest

from stitchswitch.layout.garment.design_io import load_design

from helpers import cli_run as run
from helpers import panel_design


@pytest.fixture
def design(tmp_path):
    return panel_design(tmp_path)


def test_at_grid_along_in_place(design):
    r = run("place", design, "--piece", "panel", "--at", "60,50", "-d", "40", "-p", "0.8")
    assert r.exit_code == 0, r.output
    assert "p1       (60.00, 50.00)" in r.output
    r = run("place", design, "--piece", "panel", "--grid", "2x3", "--pitch", "30",
            "-d", "30", "-p", "1", "--id-prefix", "btn", "--conductive", "ring:0")
    assert r.exit_code == 0, r.output
    r = run("place", design, "--piece", "panel", "--along", "20,180; 280,180", "--pitch", "65",
            "-d", "20", "-p", "1", "--state", "down")
    assert r.exit_code == 0, r.output
    d = load_design(design)
    ids = [p.id for p in d.patches]
    assert ids == ["p1", "btn1", "btn2", "btn3", "btn4", "btn5", "btn6", "p2", "p3", "p4", "p5", "p6"]
    grid = [p.centre_mm for p in d.patches[1:7]]
    assert grid[0] == (120.0, 115.0) and grid[-1] == (180.0, 85.0)   # centred on the centroid
    assert {p.conductive for p in d.patches[1:7]} == {"ring:0"}
    assert [p.centre_mm[0] for p in d.patches[7:]] == [20, 85, 150, 215, 280]
    assert {p.state for p in d.patches[7:]} == {"down"}


def test_output_option_leaves_the_input(design, tmp_path):
    before = design.read_bytes()
    out = tmp_path / "out.json"
    r = run("place", design, "--piece", "panel", "--grid", "1x2", "--pitch", "50",
            "--center", "100,100", "-d", "40", "-p", "1", "-o", out)
    assert r.exit_code == 0, r.output
    assert design.read_bytes() == before
    assert [p.centre_mm for p in load_design(out).patches] == [(75.0, 100.0), (125.0, 100.0)]
    again = tmp_path / "again.json"
    run("place", design, "--piece", "panel", "--grid", "1x2", "--pitch", "50",
        "--center", "100,100", "-d", "40", "-p", "1", "-o", again)
    assert again.read_bytes() == out.read_bytes()


@pytest.mark.parametrize("args,message", [
    (["-d", "40", "-p", "1"], "give exactly one of --at X,Y, --grid ROWSxCOLS or --along"),
    (["--at", "1,2", "--grid", "2x2", "-d", "40", "-p", "1"], "(got --at, --grid)"),
    (["--grid", "2x2", "-d", "40", "-p", "1"], "--grid needs --pitch MM"),
    (["--at", "1,2", "--pitch", "5", "-d", "40", "-p", "1"], "--pitch applies to --grid and --along"),
    (["--at", "1,2", "--center", "5,5", "-d", "40", "-p", "1"], "--center applies to --grid only"),
    (["--at", "1", "-d", "40", "-p", "1"], "--at '1': expected 2 numbers X,Y"),
    (["--at", "a,b", "-d", "40", "-p", "1"], "--at 'a,b': expected numbers"),
    (["--grid", "2by2", "--pitch", "5", "-d", "40", "-p", "1"], "--grid '2by2': expected ROWSxCOLS"),
    (["--grid", "0x2", "--pitch", "5", "-d", "40", "-p", "1"], "rows: 0 must be a positive integer"),
    (["--along", "1,1", "--pitch", "5", "-d", "40", "-p", "1"], "the polyline needs at least 2 points"),
    (["--at", "1,2", "-d", "40", "-p", "1.4"], "fill: 1.4 is outside (0, 1]"),
    (["--at", "1,2", "-d", "nan", "-p", "1"], "'nan' is not a finite number"),
    (["--at", "1,2", "-d", "40", "-p", "1", "--conductive", "blob"], "patch p1.conductive: unknown selection"),
])
def test_bad_input_leaves_the_file(design, args, message):
    before = design.read_bytes()
    r = run("place", design, "--piece", "panel", *args)
    assert r.exit_code == 2, r.output
    assert message in r.output and "Traceback" not in r.output
    assert design.read_bytes() == before


def test_unknown_piece_and_bad_design(design, tmp_path):
    r = run("place", design, "--piece", "sleeve", "--at", "1,2", "-d", "40", "-p", "1")
    assert r.exit_code == 2 and "no piece named 'sleeve'; the pieces are panel" in r.output
    bad = tmp_path / "bad.json"
    bad.write_text('{"version": 3}')
    r = run("place", bad, "--piece", "panel", "--at", "1,2", "-d", "40", "-p", "1")
    assert r.exit_code == 2 and "version: 3 is not a supported design file version" in r.output


def test_an_output_that_is_not_json_is_refused_before_placing(design, tmp_path):
    before = design.read_bytes()
    r = run("place", design, "--piece", "panel", "--at", "60,50", "-o", tmp_path / "out.yaml")
    assert r.exit_code == 2 and "use .json" in r.stderr and len(r.stderr.splitlines()) == 1
    assert design.read_bytes() == before and not (tmp_path / "out.yaml").exists()
