"""Inverse design under the check's fabrication rules: what breaks a rule is left out, and
fewer suggestions than asked always come with reasons."""
import pytest
from click.testing import CliRunner

from stitchswitch.cli.main import cli
from stitchswitch.errors import InvalidInputError
from stitchswitch.layout.check.constraints import check_design
from stitchswitch.layout.check.design_point import admissible, for_machine
from stitchswitch.layout.garment.design import Design, PatchSpec, PieceSpec
from stitchswitch.reduced.design_space.inverse import InverseTarget, inverse_design

TARGET = InverseTarget(12.0, max_diameter_mm=60.0, count=3)


def test_design_point_rules_agree_with_the_check():
    rule = admissible()
    for d, p in ((60.0, 0.794), (53.0, 0.842), (40.0, 0.9), (40.0, 1.0), (40.0, 0.6)):
        design = Design(1, [PieceSpec("panel", "", "t", [[0, 0], [300, 0], [300, 200], [0, 200]])],
                        [PatchSpec("a", "panel", (150, 100), d, p)], blank_margin_mm=100.0)
        flagged = {v.rule for v in check_design(design)}
        why = rule(d, p)
        assert (why is None) == (not flagged), (d, p, why, flagged)
        if why is not None:
            assert why.split(":")[0] in flagged


def test_candidates_pass_the_rules_and_the_missing_are_explained():
    free = inverse_design(TARGET)
    ruled = inverse_design(TARGET, admissible=for_machine())
    rule = for_machine()
    assert any(rule(c.diameter_mm, c.fill) for c in free.candidates)     # the rules matter here
    assert ruled.candidates and all(rule(c.diameter_mm, c.fill) is None for c in ruled.candidates)
    assert len(ruled.candidates) < TARGET.count
    assert any("feature-gap" in why for why in ruled.dropped)


def test_a_rule_that_refuses_everything_is_an_error():
    with pytest.raises(InvalidInputError, match="passes the fabrication rules"):
        inverse_design(TARGET, admissible=lambda d, p: "test rule: no")


def test_cli_says_why_fewer_came_back():
    r = CliRunner().invoke(cli, ["inverse", "--height", "12", "--max-diameter", "60",
                                 "--count", "3"])
    assert r.exit_code == 0, r.output
    assert "2 of 3 design(s) asked for:" in r.output and "feature-gap" in r.output
    r = CliRunner().invoke(cli, ["inverse", "--height", "12", "--max-diameter", "60",
                                 "--count", "3", "--no-rules"])
    assert r.exit_code == 0 and "asked for" not in r.output
