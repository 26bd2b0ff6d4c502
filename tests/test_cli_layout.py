"""stitchswitch layout: the 2D view of a design (PNG, SVG, PDF), deterministic, with the
pieces, patch ids, axes in mm, heights and violations."""
import pytest

from helpers import cli_run as run
from helpers import panel_design


@pytest.fixture
def design(tmp_path):
    path = panel_design(tmp_path, "--at", "150,100", "-d", "60", "-p", "0.7")
    assert run("place", path, "--piece", "panel", "--at", "20,20", "-d", "40", "-p", "0.7",
               "--id-prefix", "edge").exit_code == 0
    return path


def test_layout_svg_names_everything(design, tmp_path):
    svg = tmp_path / "l.svg"
    r = run("layout", design, "-o", svg)
    assert r.exit_code == 0, r.output
    assert "check   2 error(s), 0 warning(s)" in r.output
    text = svg.read_text()
    for word in ("panel", "p1", "edge1", "piece-edge, hoopable", "predicted height h (mm)",
                 "x (mm, design frame, relaxed fabric)"):
        assert word in text, word


@pytest.mark.parametrize("ext,magic", [("png", b"\x89PNG"), ("pdf", b"%PDF"), ("svg", b"<?xml")])
def test_layout_formats_are_deterministic(design, tmp_path, ext, magic):
    a, b = tmp_path / f"a.{ext}", tmp_path / f"b.{ext}"
    assert run("layout", design, "-o", a).exit_code == 0
    assert run("layout", design, "-o", b).exit_code == 0
    assert a.read_bytes().startswith(magic) and a.read_bytes() == b.read_bytes()


def test_layout_bad_input(design, tmp_path):
    r = run("layout", design, "-o", tmp_path / "l.gif")
    assert r.exit_code == 2 and r.output.startswith("Error:") and ".png, .svg or .pdf" in r.output
    assert not (tmp_path / "l.gif").exists()
    r = run("layout", tmp_path / "missing.json", "-o", tmp_path / "l.png")
    assert r.exit_code == 2 and not (tmp_path / "l.png").exists()
