"""The check's hoopable rule says exactly what fabricate refuses; an uncut blank clears it."""
import dataclasses

import numpy as np
import pytest
import shapely
from hypothesis import given, settings
from hypothesis import strategies as st

from stitchswitch.errors import InvalidInputError
from stitchswitch.layout.check.constraints import check_design
from stitchswitch.layout.check.rules import hoopable as rule
from stitchswitch.layout.check.rules.hoop import design_hoops
from stitchswitch.layout.fabrication.fabricate import FabricateOptions, fabricate
from stitchswitch.layout.garment.design import Design, MachineSpec, PatchSpec, PieceSpec

PANEL = ((0, 0), (300, 0), (300, 200), (0, 200))


def design(*centres, blank=0.0, d=40.0) -> Design:
    patches = [PatchSpec(f"p{k}", "panel", c, d, 1.0) for k, c in enumerate(centres, 1)]
    return Design(1, [PieceSpec("panel", "", "test", PANEL)], patches,
                  machine=MachineSpec("janome-550e", None), blank_margin_mm=blank)


def hoopable(d) -> list[str]:
    return [v.patches[0] for v in check_design(d) if v.rule == "hoopable"]


def fabricate_refuses(d, tmp_path, **opts) -> str | None:
    tmp_path.mkdir(exist_ok=True)
    try:
        fabricate(d, tmp_path / "out", FabricateOptions(time_limit_s=5.0, **opts))
    except InvalidInputError as exc:
        return str(exc)
    return None


@pytest.mark.parametrize("y", [20.0, 40.0, 55.0, 60.0, 100.0])
def test_check_and_fabricate_agree_on_hoopability(tmp_path, y):
    """Across the edge of what a frame allows, check and fabricate give the same verdict."""
    d = design((150.0, 100.0), (150.0, y))
    if y == 100.0:
        d = design((150.0, 100.0))
    flagged = hoopable(d)
    refused = fabricate_refuses(d, tmp_path)
    assert (refused is not None) == bool(flagged)
    if flagged:
        assert f"patch {flagged[0]!r} cannot be hooped" in refused


def test_blank_margin_clears_the_rule_and_fabricate_succeeds(tmp_path):
    d = design((150.0, 100.0), (150.0, 20.0))
    assert hoopable(d) == ["p2"]
    (v,) = [v for v in check_design(d) if v.rule == "hoopable"]
    assert v.severity == "error" and "blank" in v.hint
    wide = dataclasses.replace(d, blank_margin_mm=60.0)
    assert hoopable(wide) == []
    assert fabricate_refuses(wide, tmp_path) is None
    # the option overrides the design's field, both ways
    assert fabricate_refuses(d, tmp_path / "a", blank_margin_mm=60.0) is None
    assert fabricate_refuses(wide, tmp_path / "b", blank_margin_mm=0.0) is not None


def test_blank_margin_is_written_and_read(tmp_path):
    from stitchswitch.layout.garment.design_io import dumps_design, load_design
    d = design((150.0, 100.0), blank=25.0)
    assert '"blank_margin_mm": 25.0' in dumps_design(d)
    assert '"blank_margin_mm"' not in dumps_design(design((150.0, 100.0)))
    path = tmp_path / "d.json"
    path.write_text(dumps_design(d))
    assert load_design(path).blank_margin_mm == 25.0
    path.write_text(dumps_design(d).replace('"blank_margin_mm": 25.0', '"blank_margin_mm": -1'))
    with pytest.raises(InvalidInputError, match=r"\$\.blank_margin_mm"):
        load_design(path)


def test_model_range_is_a_rule():
    d = design((150.0, 100.0), blank=100.0, d=8.0)
    found = [v for v in check_design(d) if v.rule == "model-range"]
    assert len(found) == 1 and found[0].value == 8.0 and found[0].limit == 10.0
    assert "--diameter" in found[0].hint


# ---- can_hoop's shortcuts give the full grid's answer ------------------------------------------

def _full_grid(i, x, y, r, hoops, region) -> list:
    """Per hoop and orientation: the allowed mask of every grid point, no shortcut."""
    return [rule.allowed(region, cx.ravel(), cy.ravel(), *hoop.outer_mm(o))
            for _k, hoop, o, _w, _h, cx, cy in rule._centres(i, x, y, r, hoops, rule.STEP_MM)]


#: an L-shaped piece with a notch: a region where a disc may fit while its hoops do not
L_PIECE = ((0, 0), (420, 0), (420, 160), (200, 160), (200, 380), (0, 380))


@settings(max_examples=60, deadline=None)
@given(st.floats(-30.0, 450.0), st.floats(-30.0, 410.0), st.floats(5.0, 100.0),
       st.sampled_from([0.0, 15.0]))
def test_can_hoop_equals_the_full_grid_search(cx, cy, diameter, blank):
    """The core test and the coarse-first search change neither the verdict nor the grid's
    masks (which fabrication's placements and the frame-conflict rule use)."""
    d = Design(1, [PieceSpec("panel", "", "test", L_PIECE)],
               [PatchSpec("p1", "panel", (cx, cy), diameter, 1.0)],
               machine=MachineSpec("janome-550e", None))
    hoops = design_hoops(d)
    region = rule.hoop_region(np.asarray(L_PIECE, dtype=float), blank)
    x, y, r = np.array([cx]), np.array([cy]), np.array([diameter / 2])
    full = _full_grid(0, x, y, r, hoops, region)
    assert rule.can_hoop(0, x, y, r, hoops, region) == any(ok.any() for ok in full)
    got = [ok for *_, ok in rule.grid(0, x, y, r, hoops, region, rule.STEP_MM)]
    assert len(got) == len(full) and all(np.array_equal(a, b) for a, b in zip(got, full))


def test_the_core_lies_inside_every_outer_rectangle():
    """``core`` is inside each outer rectangle of the grid, the extreme corners included."""
    d = Design(1, [PieceSpec("panel", "", "test", PANEL)],
               [PatchSpec("p1", "panel", (150.0, 100.0), 40.0, 1.0)],
               machine=MachineSpec("janome-550e", None))
    x, y, r = np.array([150.0]), np.array([100.0]), np.array([20.0])
    seen = 0
    for _k, hoop, o, w, h, cx, cy in rule._centres(0, x, y, r, design_hoops(d), rule.STEP_MM):
        ow, oh = hoop.outer_mm(o)
        c = rule.core(150.0, 100.0, 20.0, w, h, ow, oh)
        boxes = shapely.box(cx - ow / 2, cy - oh / 2, cx + ow / 2, cy + oh / 2).ravel()
        assert shapely.contains(boxes, c).all()
        seen += 1
    assert seen >= 4
