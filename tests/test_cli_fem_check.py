import json

from click.testing import CliRunner

from stitchswitch.cli.main import cli


def test_fem_check_model_error_table_attributes_the_gap(tmp_path):
    result = CliRunner().invoke(cli, ["fem-check", "--designs", "90,0.8", "--report", str(tmp_path / "r"),
                                      "--json"])
    assert result.exit_code in (0, 1), result.output
    out = json.loads(result.output)
    row = out["rows"][0]
    assert row["certified"]
    # the shell with the reduced model's physics is close to the reduced model: the gap is physics
    assert abs(row["remainder_mm"]["h_mm"]) < 0.5
    # the tension-field knit raises the dome: turning it off lowers h by more than a millimetre
    assert row["attribution_mm"]["relaxed_membrane"]["h_mm"] < -1.0
    assert row["attribution_mm"]["natural_curvature"]["h_mm"] == 0.0       # kappa0 = 0
    total = (row["remainder_mm"]["h_mm"] + row["interaction_mm"]["h_mm"]
             + sum(a["h_mm"] for a in row["attribution_mm"].values()))
    assert abs(total - row["gap_mm"]["h_mm"]) < 1e-9
    assert out["passed"]["r_a_mm"] and out["all_passed"] == (result.exit_code == 0)
    assert (tmp_path / "r" / "report.md").exists() and (tmp_path / "r" / "report.json").exists()


def test_fem_check_text_names_the_budget():
    result = CliRunner().invoke(cli, ["fem-check", "--designs", "90,1", "--elements", "20"])
    assert result.exit_code in (0, 1)
    assert "PASS   r_a within 7.9 % or 0.91 mm" in result.output
    assert "relax" in result.output.splitlines()[0]


def test_fem_check_bad_designs():
    result = CliRunner().invoke(cli, ["fem-check", "--designs", "40;0.8"])
    assert result.exit_code == 2 and "--designs" in result.output
    result = CliRunner().invoke(cli, ["fem-check", "--designs", "400,0.8"])
    assert result.exit_code == 2 and "400,0.8" in result.output


def test_fem_check_report_path_is_checked_before_computing(tmp_path):
    f = tmp_path / "file"
    f.write_text("x")
    result = CliRunner().invoke(cli, ["fem-check", "--designs", "90,1", "--report", str(f)])
    assert result.exit_code == 2 and "--report" in result.output


def test_fem_solve_writes_a_mesh_with_the_height(tmp_path):
    import meshio

    out = tmp_path / "dome.vtu"
    result = CliRunner().invoke(cli, ["fem-solve", "-d", "90", "-p", "0.8", "--elements", "20",
                                      "--mesh", str(out), "--json"])
    assert result.exit_code == 0, result.output
    res = json.loads(result.output)
    assert res["certified"]
    m = meshio.read(out)
    assert abs((m.points[:, 2].max() - m.points[:, 2].min()) - res["h_mm"]) < 0.01
