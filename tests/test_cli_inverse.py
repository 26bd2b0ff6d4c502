import json

from click.testing import CliRunner

from stitchswitch.cli.main import cli


def test_inverse_json():
    result = CliRunner().invoke(cli, ["inverse", "--height", "17.5", "--count", "3", "--json"])
    assert result.exit_code == 0, result.output
    out = json.loads(result.output)
    assert 1 <= len(out["candidates"]) <= 3
    for c in out["candidates"]:
        assert {"d_mm", "fill", "h_mm", "r_a_mm", "z_a_mm", "r_b_mm", "z_b_mm", "force_N"} <= set(c)
        assert abs(c["h_mm"] - 17.5) <= 0.2


def test_inverse_table():
    result = CliRunner().invoke(cli, ["inverse", "--height", "8", "--max-diameter", "50"])
    assert result.exit_code == 0, result.output
    assert "d_mm" in result.output and "certified" in result.output


def test_unreachable_exits_2_with_the_range():
    result = CliRunner().invoke(cli, ["inverse", "--height", "35"])
    assert result.exit_code == 2
    assert "not achievable" in result.output and "ranges from" in result.output
    assert "Traceback" not in result.output and len(result.output.strip().splitlines()) == 1


def test_bad_options_exit_2():
    for args in (["--height", "nan"], ["--height", "5", "--min-fill", "2"], ["--height", "5", "--count", "0"],
                 ["--height", "5", "--force-range", "0.5", "0.1"]):
        result = CliRunner().invoke(cli, ["inverse", *args])
        assert result.exit_code == 2, (args, result.output)
        assert "Traceback" not in result.output
