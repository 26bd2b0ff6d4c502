"""Bistable or spring-back: the inverted state as a strict local minimum without load."""
import json

from click.testing import CliRunner

from stitchswitch import Patch
from stitchswitch.cli.main import cli
from stitchswitch.fem_reference.revolution import ShellParams
from stitchswitch.fem_reference.snap import bistability


def test_symmetric_layer_is_bistable():
    b = bistability(Patch(60.0, 0.8))
    assert b.verdict == "bistable"
    assert b.inverted.certified and b.inverted.apex_mm < 0
    assert abs(b.inverted.energy - b.popup.energy) < 1e-9 * abs(b.popup.energy)


def test_natural_curvature_makes_a_small_patch_spring_back():
    b = bistability(Patch(40.0, 0.7), params=ShellParams(kappa0_per_mm=0.1))
    assert b.popped and b.popup.certified
    assert b.verdict == "spring-back"
    assert b.inverted.apex_mm > 0                  # the mirror image relaxed back to pop-up
    assert bistability(Patch(40.0, 0.7)).verdict == "flat"


def test_bistability_map_cli(tmp_path):
    png = tmp_path / "map.png"
    result = CliRunner().invoke(cli, ["bistability-map", "--diameters", "40,60", "--fills", "0.7,0.8",
                                      "--kappa0", "0.1", "--png", str(png), "--json"])
    assert result.exit_code == 0, result.output
    out = json.loads(result.output)
    assert out["verdicts"][0][0] == "spring-back" and out["kappa0_per_mm"] == 0.1
    assert png.read_bytes()[:4] == b"\x89PNG"


def test_bistability_map_bad_input(tmp_path):
    for args, name in ((["--kappa0", "-0.1"], "--kappa0"), (["--diameters", "a,b"], "--diameters"),
                       (["--fills", "0.5,1.5"], "--fills"), (["--png", str(tmp_path)], "--png")):
        result = CliRunner().invoke(cli, ["bistability-map", *args])
        assert result.exit_code == 2 and name in result.output, (args, result.output)
