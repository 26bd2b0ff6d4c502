"""stitchswitch edit / remove, and what place prints: predictions, warnings, refusals."""
import json

import pytest

from helpers import cli_run as run
from helpers import panel_design


@pytest.fixture
def design(tmp_path):
    return panel_design(tmp_path, "--grid", "1x2", "--pitch", "80", "-d", "40", "-p", "0.7")


def patches(path):
    return {p["id"]: p for p in json.loads(path.read_text())["patches"]}


def test_place_prints_prediction_and_footprint(design):
    r = run("place", design, "--piece", "panel", "--at", "150,150", "-d", "40", "-p", "0.7")
    assert r.exit_code == 0, r.output
    line = next(x for x in r.output.splitlines() if x.startswith("p3 "))
    assert "h = " in line and "r_a = " in line
    assert f"footprint {40 / 1.7:.1f} mm relaxed, 40 mm stretched" in line
    assert "Warning:" not in r.output


def test_place_warns_on_what_check_flags(design):
    r = run("place", design, "--piece", "panel", "--at", "10,10", "-d", "40", "-p", "0.7")
    assert r.exit_code == 0
    warnings = [x for x in r.output.splitlines() if x.startswith("Warning:")]
    assert [w.split(":")[1].strip() for w in warnings] == ["piece-edge", "hoopable"]
    check = run("check", design, "--json")
    assert {v["rule"] for v in json.loads(check.output)["violations"]} == {"piece-edge", "hoopable"}


@pytest.mark.parametrize("args,message", [
    (["--at", "-400,0", "-d", "40", "-p", "0.7"], "outside piece panel"),
    (["--at", "150,100", "-d", "200", "-p", "0.7"], "outside the model's range [10, 150]"),
    (["--at", "150,100"], "give --diameter and --fill, or --height"),
    (["--at", "150,100", "-d", "40", "-p", "0.7", "--radius", "10"], "--radius applies to --height"),
])
def test_place_refuses_impossible_input(design, args, message):
    before = design.read_bytes()
    r = run("place", design, "--piece", "panel", *args)
    assert r.exit_code == 2 and message in r.output
    assert design.read_bytes() == before


def test_edit_moves_and_keeps_the_id(design):
    r = run("edit", design, "p2", "--at", "150,20")
    assert r.exit_code == 0, r.output
    assert patches(design)["p2"]["centre_mm"] == [150.0, 20.0]
    assert list(patches(design)) == ["p1", "p2"]
    assert "Warning: piece-edge" in r.output and "Warning: hoopable" in r.output
    r = run("edit", design, "p2", "--at", "190,100", "-p", "0.75")
    assert r.exit_code == 0 and "Warning" not in r.output
    assert patches(design)["p2"]["fill"] == 0.75
    assert run("check", design).exit_code == 0


@pytest.mark.parametrize("args,message", [
    (["p9", "--at", "1,1"], "no patch with id 'p9'; the patches are p1, p2"),
    (["p1"], "patch p1: nothing to change"),
    (["p1", "-d", "300"], "outside the model's range"),
    (["p1", "--piece", "back"], "no piece named 'back'"),
    (["p1", "-p", "1.5"], "patch p1.fill: 1.5 is outside (0, 1]"),
])
def test_edit_bad_input_changes_nothing(design, args, message):
    before = design.read_bytes()
    r = run("edit", design, *args)
    assert r.exit_code == 2 and message in r.output, r.output
    assert design.read_bytes() == before


def test_remove(design, tmp_path):
    out = tmp_path / "out.json"
    r = run("remove", design, "p1", "-o", out)
    assert r.exit_code == 0, r.output
    assert list(patches(out)) == ["p2"] and list(patches(design)) == ["p1", "p2"]
    for args, message in ((["p7"], "no patch with id 'p7'"), (["p1", "p1"], "named twice")):
        r = run("remove", design, *args)
        assert r.exit_code == 2 and message in r.output


def test_place_for_height_under_the_rules(design):
    r = run("place", design, "--piece", "panel", "--at", "150,150", "--height", "12")
    assert r.exit_code == 0, r.output
    new = patches(design)["p3"]
    from stitchswitch.layout.check.design_point import for_machine
    assert for_machine()(new["diameter_mm"], new["fill"]) is None
    line = next(x for x in r.output.splitlines() if x.startswith("p3 "))
    h = float(line.split("h = ")[1].split(" mm")[0])
    assert h == pytest.approx(12.0, abs=0.2)
    assert "Warning" not in r.output
