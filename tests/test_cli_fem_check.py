import json

from click.testing import CliRunner

from stitchswitch.cli.main import cli


def test_fem_check_one_large_design_meets_the_targets(tmp_path):
    result = CliRunner().invoke(cli, ["fem-check", "--designs", "90,1", "--report", str(tmp_path / "r"), "--json"])
    assert result.exit_code == 0, result.output
    out = json.loads(result.output)
    row = out["rows"][0]
    rel = [abs(row["reduced"][n]["rel_r_a_mm"]) for n in ("75", "150", "300", "600")]
    assert all(a > b for a, b in zip(rel, rel[1:]))            # converges towards the reference
    assert out["targets"]["h_mm"]["met"] and out["targets"]["r_a_mm"]["met"]
    assert (tmp_path / "r" / "report.md").exists() and (tmp_path / "r" / "report.json").exists()


def test_fem_check_small_patch_misses_the_h_target_and_says_so():
    result = CliRunner().invoke(cli, ["fem-check", "--designs", "25,0.6", "--start", "reduced"])
    assert result.exit_code == 1
    assert "FAIL  h_mm" in result.output


def test_fem_check_bad_designs():
    result = CliRunner().invoke(cli, ["fem-check", "--designs", "40;0.8"])
    assert result.exit_code == 2 and "--designs" in result.output


def test_fem_solve_writes_a_mesh_with_the_height(tmp_path):
    import meshio

    out = tmp_path / "dome.vtu"
    result = CliRunner().invoke(cli, ["fem-solve", "-d", "50", "-p", "0.8", "--elements", "20",
                                      "--mesh", str(out), "--json"])
    assert result.exit_code == 0, result.output
    res = json.loads(result.output)
    assert res["converged"]
    m = meshio.read(out)
    assert abs((m.points[:, 2].max() - m.points[:, 2].min()) - res["h_mm"]) < 0.01


def test_variant_terms_attribute_the_gap():
    """The paper's first-order quadrature of the boundary ring, measured against the default
    trapezoid rule: at N = 300 it puts r_a several times further from the reference."""
    from stitchswitch import Patch
    from stitchswitch.fem_reference.check import check_design

    row = check_design(Patch(90.0, 1.0), start="reduced")
    assert abs(row.paper_indexing_300_rel["r_a_mm"]) > 3.0 * abs(row.at(300).rel["r_a_mm"])


def test_fem_solve_by_continuation_matches_the_reduced_start():
    args = ["fem-solve", "-d", "60", "-p", "1", "--elements", "30", "--json"]
    by_reduced = CliRunner().invoke(cli, args + ["--start", "reduced"])
    by_continuation = CliRunner().invoke(cli, args)
    assert by_reduced.exit_code == 0 and by_continuation.exit_code == 0, by_continuation.output
    a, b = json.loads(by_reduced.output), json.loads(by_continuation.output)
    assert a["start"] == "reduced" and b["start"] == "continuation" and b["converged"]
    for k in ("h_mm", "r_a_mm", "z_a_mm", "r_b_mm", "z_b_mm"):
        assert abs(b[k] - a[k]) <= 5e-3 * abs(a[k]), k


def test_fem_check_starts_by_continuation_unless_told():
    by_default = CliRunner().invoke(cli, ["fem-check", "--designs", "90,0.8", "--json"])
    by_reduced = CliRunner().invoke(cli, ["fem-check", "--designs", "90,0.8", "--start", "reduced",
                                          "--json"])
    assert by_default.exit_code == 0 and by_reduced.exit_code == 0, by_default.output
    a, b = json.loads(by_default.output), json.loads(by_reduced.output)
    assert a["start"] == "continuation" and b["start"] == "reduced"
    for k, v in b["rows"][0]["reference"].items():            # the same reference equilibrium
        assert abs(a["rows"][0]["reference"][k] - v) <= 1e-6 * abs(v), k


def test_fem_solve_bad_start():
    result = CliRunner().invoke(cli, ["fem-solve", "-d", "50", "-p", "0.8", "--start", "flat"])
    assert result.exit_code == 2 and "--start" in result.output
