
import pytest
from click.testing import CliRunner

from stitchswitch.cli.main import cli

from helpers import EXTERNAL

STAR = EXTERNAL / "embroidery"


@pytest.mark.parametrize("name", ["Star.DST", "Star.JEF", "Star.EXP", "Star.pes"])
def test_inspect_star(name):
    r = CliRunner().invoke(cli, ["inspect", str(STAR / name)])
    assert r.exit_code == 0, r.output
    assert "extents   59.1 x 62.3 mm" in r.output
    assert "SQ14b 140 x 140 mm" in r.output


def test_inspect_own_file_counts_trims(tmp_path):
    out = tmp_path / "p.jef"
    assert CliRunner().invoke(cli, ["patch", "-d", "40", "-p", "0.8", "-o", str(out)]).exit_code == 0
    r = CliRunner().invoke(cli, ["inspect", str(out)])
    assert r.exit_code == 0
    lines = dict(line.split(None, 1) for line in r.output.strip().splitlines())
    assert int(lines["trims"]) > 0 and lines["colours"].startswith("1")


def test_inspect_bad_file(tmp_path):
    bad = tmp_path / "x.txt"
    bad.write_text("hello")
    r = CliRunner().invoke(cli, ["inspect", str(bad)])
    assert r.exit_code == 2 and r.output.startswith("Error: ")
    r = CliRunner().invoke(cli, ["inspect", str(tmp_path / "missing.jef")])
    assert r.exit_code == 2 and "no such file" in r.output


@pytest.mark.parametrize("name, content, message", [
    ("e.DST", b"x", "1 bytes, too short for a DST file (at least 512)"),
    ("e.DST", b"", "0 bytes, too short for a DST file"),
    ("e.DST", b"LA:" + b" " * 509 + b"\x00\x00\xf3", "holds no stitches (not a DST design)"),
    ("e.pes", b"#PEC0001" + b"\x00" * 100, "not a PES file (it does not start with #PES)"),
    ("e.pes", b"#PES0001" + b"\xff" * 40, "not a readable PES file (malformed data)"),
    ("e.jef", b"\x00" * 200, "stitches lie at one point (not a JEF design)"),
    ("e.xyz", b"abc", "'xyz' is not an embroidery format pyembroidery reads"),
])
def test_empty_and_garbage_files_are_refused(tmp_path, name, content, message):
    """Empty or garbage files are one error naming the file, never a design of 0 stitches
    that fits every hoop, and never pyembroidery's own exception text."""
    bad = tmp_path / name
    bad.write_bytes(content)
    r = CliRunner().invoke(cli, ["inspect", str(bad)])
    assert r.exit_code == 2 and r.output.count("\n") == 1, r.output
    assert r.output.startswith(f"Error: {str(bad)!r}: ") and message in r.output
