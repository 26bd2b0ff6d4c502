import json

from click.testing import CliRunner

from stitchswitch.cli.main import cli
from stitchswitch.reduced.design_space.storage import load_map


def test_precompute_small_grid_writes_map_and_plot(tmp_path):
    out, png = tmp_path / "m.npz", tmp_path / "m.png"
    result = CliRunner().invoke(cli, ["precompute", "--diameters", "30:33:1", "--fills", "0.7:0.73:0.01",
                                      "--workers", "1", "-o", str(out), "--plot", str(png)])
    assert result.exit_code == 0, result.output
    assert "4 x 4 designs" in result.output and "all certified: yes" in result.output
    dmap = load_map(out)
    assert dmap.shape == (4, 4) and dmap.converged.all()
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_precompute_json(tmp_path):
    result = CliRunner().invoke(cli, ["precompute", "--diameters", "30:31:1", "--fills", "0.7:0.71:0.01",
                                      "--workers", "1", "-o", str(tmp_path / "m.npz"), "--json"])
    assert result.exit_code == 0, result.output
    summary = json.loads(result.output.strip().splitlines()[-1])
    assert summary["n_diameters"] == 2 and summary["all_converged"] is True
    assert summary["flagged"] == []


def test_precompute_bad_input_exits_2_without_output(tmp_path):
    out = tmp_path / "m.npz"
    for args in (["--diameters", "30:x"], ["--fills", "0.5:1.2:0.1"], ["--diameters", "5:20:1"],
                 ["--workers", "0"]):
        result = CliRunner().invoke(cli, ["precompute", *args, "-o", str(out)])
        assert result.exit_code == 2, (args, result.output)
        assert "Traceback" not in result.output
        assert not out.exists()
    result = CliRunner().invoke(cli, ["precompute", "--fills", "0.5:1.2:0.1", "-o", str(out)])
    assert "fill" in result.output and "1.2" in result.output


def test_out_is_a_deprecated_alias_of_output(tmp_path):
    out = tmp_path / "m.npz"
    r = CliRunner().invoke(cli, ["precompute", "--diameters", "30:31:1", "--fills", "0.8:0.81:0.01",
                                 "--workers", "1", "--out", str(out), "--json"])
    assert r.exit_code == 0, r.output
    assert "Warning: --out is deprecated; use -o/--output" in r.stderr
    import json
    json.loads(r.stdout)                                  # stdout stays pure JSON
    assert out.exists()
    r = CliRunner().invoke(cli, ["precompute", "--out", str(out), "-o", str(out)])
    assert r.exit_code == 2 and "not both" in r.output
    r = CliRunner().invoke(cli, ["precompute"])
    assert r.exit_code == 2 and "Missing option '-o/--output'" in r.output
