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
    result = CliRunner().invoke(cli, ["fem-check", "--designs", "25,0.6"])
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
    """Swapping the hoop term's boundary quadrature is measured, and it shrinks the h gap."""
    from stitchswitch.fem_reference.check import check_design
    from stitchswitch import Patch

    row = check_design(Patch(25.0, 0.8))
    assert abs(row["hoop_node_average_300"]["rel_h_mm"]) < 0.75 * abs(row["reduced"]["300"]["rel_h_mm"])
