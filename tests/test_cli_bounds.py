"""Options whose values past a range make a command run away or compute nonsense are refused
before any work: one error naming the option and the value, exit code 2, and the range stated
in ``--help``."""
import pytest
from click.testing import CliRunner

from stitchswitch.cli.main import cli


@pytest.mark.parametrize("args, words", [
    (["precompute", "--diameters", "30:31:1e-9", "-o", "m.npz"], ["--diameters", "at most 2000"]),
    (["precompute", "--fills", "0.5:1:1e-7", "-o", "m.npz"], ["--fills", "at most 2000"]),
    (["patch", "-d", "40", "-p", "0.8", "--row-spacing", "1e-6", "-o", "p.jef"], ["--row-spacing", "1e-06"]),
    (["patch", "-d", "40", "-p", "0.8", "--row-spacing", "9", "-o", "p.jef"], ["--row-spacing", "[0.1, 5]"]),
    (["fem-check", "--designs", "90,1", "--poisson", "0.7"], ["--poisson", "0.7", "(-1, 0.5]"]),
    (["fem-solve", "-d", "50", "-p", "0.8", "--poisson", "-1"], ["--poisson", "-1", "(-1, 0.5]"]),
])
def test_out_of_range_option_is_refused_before_any_work(tmp_path, monkeypatch, args, words):
    monkeypatch.chdir(tmp_path)
    result = CliRunner().invoke(cli, args)
    assert result.exit_code == 2, result.output
    for w in words:
        assert w in result.output, (w, result.output)
    assert "Traceback" not in result.output
    assert not any(p.exists() for p in (tmp_path / "m.npz", tmp_path / "p.jef"))


def test_a_huge_grid_is_refused(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    runner = CliRunner()
    assert runner.invoke(cli, ["import", "--rectangle", "300x200", "-o", "d.json"]).exit_code == 0
    before = (tmp_path / "d.json").read_text()
    result = runner.invoke(cli, ["place", "d.json", "--piece", "rectangle", "--grid", "2000x2000",
                                 "--pitch", "60", "-d", "45", "-p", "0.74"])
    assert result.exit_code == 2 and "--grid '2000x2000'" in result.output, result.output
    assert (tmp_path / "d.json").read_text() == before


@pytest.mark.parametrize("command, text", [(["patch"], "[0.1, 5] mm"), (["fem-check"], "(-1, 0.5]"),
                                           (["place"], "at most 100 a side"),
                                           (["precompute"], "at most 2000 values")])
def test_the_range_is_in_the_help(command, text):
    out = CliRunner().invoke(cli, [*command, "--help"]).output
    assert text in " ".join(out.split()), out
