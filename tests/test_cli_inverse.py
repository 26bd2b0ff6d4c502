import json

import pytest
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


def test_inverse_on_a_given_map_uses_its_material(tmp_path):
    import numpy as np

    from stitchswitch.reduced.design_space import precompute
    from stitchswitch.reduced.design_space import storage as map_io
    from stitchswitch.reduced.model.params import DEFAULT_MATERIAL

    other = DEFAULT_MATERIAL.replace(w_b_emb=12.0)
    small = precompute.build(other, np.arange(40.0, 46.0), np.round(np.arange(0.7, 0.86, 0.05), 2),
                             check=False)
    path = tmp_path / "m.npz"
    map_io.save_map(small, path)
    r = CliRunner().invoke(cli, ["inverse", "--height", "5", "--map", str(path), "--count", "1",
                                 "--json"])
    assert r.exit_code == 0, r.output
    (c,) = json.loads(r.output)["candidates"]
    assert 40 <= c["d_mm"] <= 45
    from stitchswitch import Patch, solve
    assert solve(Patch(c["d_mm"], c["fill"]), other).keypoints.h_mm == pytest.approx(c["h_mm"], abs=1e-9)
    assert abs(c["h_mm"] - 5.0) <= 0.2


def test_inverse_material_and_map_together_is_an_error(tmp_path):
    r = CliRunner().invoke(cli, ["inverse", "--height", "12", "--map", "x.npz",
                                 "--material", "y.json"])
    assert r.exit_code == 2 and "give --material or --map, not both" in r.output
