"""stitchswitch check: table and JSON, exit 0 clean / 1 violations / 2 bad input."""
import json

import pytest

from helpers import cli_run as run
from helpers import panel_design


@pytest.fixture
def design(tmp_path):
    return panel_design(tmp_path, "--grid", "2x2", "--pitch", "40", "-d", "40", "-p", "1")


def test_clean_exit_0(design):
    r = run("check", design)
    assert r.exit_code == 0, r.output
    assert r.output == "4 patch(es) on 1 piece(s): no violation\n"
    out = json.loads(run("check", design, "--json").output)
    assert out["clean"] is True and out["violations"] == [] and out["patches"] == 4
    assert out["limits"]["seam_allowance_mm"] == 10.0 and out["limits"]["hoop_margin_mm"] is None


def test_violations_exit_1_table_and_json(design):
    assert run("place", design, "--piece", "panel", "--at", "30,30", "-d", "60", "-p", "0.9",
               "--id-prefix", "pocket").exit_code == 0
    r = run("check", design)
    assert r.exit_code == 1
    lines = r.output.splitlines()
    assert lines[0].split()[:6] == ["severity", "rule", "patches", "pieces", "value", "mm"]
    assert lines[1].split()[:5] == ["error", "piece-edge", "pocket1", "panel", "12.35"]
    assert lines[2].split()[0] == "fix:" and "move it at least" in lines[2]
    assert lines[3].split()[:5] == ["warning", "feature-gap", "pocket1", "panel", "0.15"]
    # its footprint crosses the outline, so no hoop frame can lie on the cut piece either
    assert lines[5].split()[:4] == ["error", "hoopable", "pocket1", "panel"]
    assert "--blank-margin" in lines[6]
    assert lines[-1] == "5 patch(es) on 1 piece(s): 2 error(s), 1 warning(s)"
    j = run("check", design, "--json")
    assert j.exit_code == 1
    out = json.loads(j.output)
    assert out["errors"] == 2 and out["warnings"] == 1 and not out["clean"]
    assert [v["rule"] for v in out["violations"]] == ["piece-edge", "feature-gap", "hoopable"]
    assert all(v["hint"] for v in out["violations"])
    v = out["violations"][0]
    assert v["rule"] == "piece-edge" and v["patches"] == ["pocket1"] and v["limit"] == 15.0
    assert v["value"] == pytest.approx(30 - 30 / 1.7)


def test_limit_options_change_the_result(design):
    assert run("place", design, "--piece", "panel", "--at", "30,30", "-d", "60", "-p", "0.8",
               "--id-prefix", "pocket").exit_code == 0
    r = run("check", design, "--seam-allowance", "5", "--edge-clearance", "0", "--min-gap", "0.3")
    assert r.exit_code == 1 and "hoopable" in r.output      # no room for a frame on the cut piece
    r = run("check", design, "--seam-allowance", "5", "--edge-clearance", "0", "--min-gap", "0.3",
            "--blank-margin", "60")
    assert r.exit_code == 0, r.output
    r = run("check", design, "--min-spacing", "20", "--seam-allowance", "5",
            "--edge-clearance", "0", "--min-gap", "0.3", "--blank-margin", "60")
    assert r.exit_code == 1 and "spacing" in r.output


def test_geometry_violation_prints_no_value(tmp_path, design):
    assert run("place", design, "--piece", "panel", "--at", "150,150", "-d", "20", "-p", "1",
               "--conductive", "index:500").exit_code == 0
    r = run("check", design, "--json")
    v = json.loads(r.output)["violations"]
    assert r.exit_code == 1 and v[0]["rule"] == "geometry" and v[0]["value"] is None


def test_library_report_is_what_check_prints(tmp_path, design):
    """``check_report`` (what the demo writes as check.json) gives the CLI's JSON body, and a
    rule with no measured value is null there too, so it serializes without NaN."""
    from stitchswitch.layout.check.report import check_report
    from stitchswitch.layout.garment.design_io import load_design

    assert run("place", design, "--piece", "panel", "--at", "150,150", "-d", "20", "-p", "1",
               "--conductive", "index:500").exit_code == 0
    out = json.loads(run("check", design, "--json").output)
    body = json.loads(json.dumps(check_report(load_design(design)).as_dict(), allow_nan=False))
    assert body["violations"][0]["value"] is None and body["errors"] >= 1
    assert body == {k: out[k] for k in body}


@pytest.mark.parametrize("args,message", [
    (["--min-gap", "-1"], "min_gap_mm: -1.0 must be >= 0"),
    (["--resolution", "nan"], "'nan' is not a finite number"),
])
def test_bad_limits_exit_2(design, args, message):
    r = run("check", design, *args)
    assert r.exit_code == 2 and message in r.output


def test_bad_design_exit_2(tmp_path):
    r = run("check", tmp_path / "none.json")
    assert r.exit_code == 2 and "cannot be read" in r.output
    bad = tmp_path / "bad.json"
    bad.write_text(json.dumps({"version": 1, "pieces": [], "patches": [
        {"id": "a", "piece": "x", "centre_mm": [0, 0], "diameter_mm": 40, "fill": 1.4}]}))
    r = run("check", bad)
    assert r.exit_code == 2 and "patches[0].piece: 'x' is not a piece" in r.output
    assert "Traceback" not in r.output


def test_small_pieces_are_a_warning_as_fabricate_gives_it(tmp_path):
    """A d 100 p 0.6 patch has boundary slivers under 1 mm^2: check warns (text and --json)
    with the count fabricate's sheet and fabrication.json give, and keeps exit code 0."""
    from stitchswitch.layout.embroidery.stitches import small_pieces_text
    from test_cli_fabricate import patch, write_design

    design = write_design(tmp_path / "d.json", [patch("a", 80, 80, 100, 0.6),
                                                patch("b", 220, 170, 24, 0.8)])
    r = run("check", design)
    assert r.exit_code == 0, r.output
    warned = [line for line in r.output.splitlines() if line.startswith("warning: ")]
    assert len(warned) == 1 and warned[0].startswith("warning: patch a: ")
    assert r.output.splitlines()[-1] == ("2 patch(es) on 1 piece(s): no violation; small pieces "
                                         "in 1 patch(es)")
    j = run("check", design, "--json")
    assert j.exit_code == 0
    out = json.loads(j.output)
    assert out["clean"] is True and out["violations"] == [] and out["warnings"] == 0
    (w,) = out["small_pieces"]
    assert (w["patch"], w["piece"], w["area_mm2"]) == ("a", "front", 1.0) and w["count"] > 0
    assert w["message"] == f"patch a: {small_pieces_text(w['count'])}" == warned[0][9:]
    f = run("fabricate", design, "-o", tmp_path / "fab")
    assert f.exit_code == 0, f.output
    doc = json.loads((tmp_path / "fab" / "fabrication.json").read_text())
    counts = {p["id"]: 0 for h in doc["hoopings"] for p in h["patches"]}
    counts["a"] = w["count"]
    for h in doc["hoopings"]:
        assert h["small_pieces"] == sum(counts[p["id"]] for p in h["patches"])
        if h["small_pieces"]:
            assert small_pieces_text(h["small_pieces"]) in (tmp_path / "fab" / "fabrication.md").read_text()
    # a design without small pieces: no warning line, an empty list
    clean = write_design(tmp_path / "c.json", [patch("b", 220, 170, 24, 0.8)])
    assert "warning" not in run("check", clean).output
    assert json.loads(run("check", clean, "--json").output)["small_pieces"] == []
