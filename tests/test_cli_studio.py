"""``stitchswitch studio``'s bad input: one ``Error:`` line naming the value, exit code 2, nothing
written and no server started. (A good run serves the page: tests/test_studio_browser.py.)"""
import pytest
from click.testing import CliRunner

from stitchswitch.cli.main import cli
from stitchswitch.layout.garment.design import Design
from stitchswitch.layout.garment.design_io import save_design
from stitchswitch.layout.garment.piece_select import rectangle_piece

pytest.importorskip("trame")


def run(*args):
    return CliRunner().invoke(cli, ["studio", *args])


def one_error(result, *words):
    assert result.exit_code == 2, result.output
    lines = [ln for ln in result.output.splitlines() if ln.strip()]
    assert len(lines) == 1 and lines[0].startswith("Error:") and "Traceback" not in result.output
    for w in words:
        assert w in lines[0]


def test_neither_or_both_sources(tmp_path):
    one_error(run("--no-browser"), "--rectangle")
    path = tmp_path / "d.json"
    save_design(Design(1, (rectangle_piece(300.0, 200.0),), ()), path)
    one_error(run(str(path), "--rectangle", "300x200", "--no-browser"), "not both")


def test_rectangle_needs_a_new_output(tmp_path):
    one_error(run("--rectangle", "300x200", "--no-browser"), "--output")
    taken = tmp_path / "taken.json"
    taken.write_text("{}")
    one_error(run("--rectangle", "300x200", "-o", str(taken), "--no-browser"), "taken.json", "exists")
    assert taken.read_text() == "{}"
    one_error(run("--rectangle", "300xbad", "-o", str(tmp_path / "n.json"), "--no-browser"), "300xbad")
    assert not (tmp_path / "n.json").exists()


def test_bad_design_file(tmp_path):
    bad = tmp_path / "bad.json"
    bad.write_text('{"version": 1, "pieces": [], "patches": [{"id": 3}]}')
    one_error(run(str(bad), "--no-browser"), "bad.json")
    assert not (tmp_path / "bad.json.autosave.json").exists()


def test_size_needs_a_pattern(tmp_path):
    one_error(run("--rectangle", "300x200", "--size", "36", "-o", str(tmp_path / "n.json"),
                  "--no-browser"), "--size")
    path = tmp_path / "d.json"
    save_design(Design(1, (rectangle_piece(300.0, 200.0),), ()), path)
    one_error(run(str(path), "--size", "36", "--no-browser"), "--size")
    assert not (tmp_path / "n.json").exists()


def test_an_unknown_view_mode(tmp_path):
    path = tmp_path / "d.json"
    save_design(Design(1, (rectangle_piece(300.0, 200.0),), ()), path)
    one_error(run(str(path), "--view", "gpu", "--no-browser"), "--view", "gpu")
    assert not (tmp_path / "d.json.autosave.json").exists()
