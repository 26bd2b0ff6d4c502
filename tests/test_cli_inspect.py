
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
