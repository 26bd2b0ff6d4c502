"""Rule ``frame-conflict``: two patches whose hoopings must press one another with the frame
are flagged by the check, and the fabrication plan indeed leaves a conflict there; patches a
hoop holds together, or far enough apart, are not."""
import numpy as np
import pytest

from stitchswitch.layout.check.constraints import check_design
from stitchswitch.layout.fabrication.grouping.footprints import stretch
from stitchswitch.layout.fabrication.grouping.group import group
from stitchswitch.layout.fabrication.order import order_hoopings
from stitchswitch.layout.garment.design_io import load_design
from test_cli_fabricate import patch, write_design

ETA = 1.7


def _design(tmp_path, gap_mm, hoop="SQ14b", d=70.0):
    """Two d mm patches whose footprints are ``gap_mm`` apart on the stretched fabric."""
    rows = [patch("a", 100, 100, d, 0.8), patch("b", 100 + (d + gap_mm) / ETA, 100, d, 0.8)]
    return load_design(write_design(tmp_path / "d.json", rows, hoop=hoop))


def _conflicts(design):
    feet, pieces = stretch(design, ETA)
    from stitchswitch.layout.check.rules.hoop import design_hoops
    g = group(feet, pieces, design_hoops(design), "garment")
    return len(order_hoopings(g.hoopings, feet).conflicts)


def test_forced_pair_flagged_and_fabrication_agrees(tmp_path):
    design = _design(tmp_path, 25.0)
    found = [v for v in check_design(design) if v.rule == "frame-conflict"]
    assert len(found) == 1
    v = found[0]
    assert v.severity == "warning" and v.patches == ("a", "b") and v.limit == 25
    assert v.value == pytest.approx(25.0)
    assert "move them apart" in v.hint
    assert _conflicts(design) == 1


@pytest.mark.parametrize("gap, hoop", [(25.0, None),        # the RE20b holds both
                                       (60.0, "SQ14b")])    # a frame fits between them
def test_no_warning_when_avoidable(tmp_path, gap, hoop):
    design = _design(tmp_path, gap, hoop)
    assert not [v for v in check_design(design) if v.rule == "frame-conflict"]
    assert _conflicts(design) == 0


@pytest.mark.parametrize("seed", [0, 1, 3, 10])
def test_flagged_pairs_are_a_lower_bound_of_the_plan(tmp_path, seed):
    """Every flagged pair costs a conflict in any plan: the exact plan (4 patches) has at
    least as many conflicts as there are disjoint flagged pairs (seeds 1, 3: one pair and one
    conflict; 10: two pairs sharing a patch, two conflicts; 0: none)."""
    rng = np.random.default_rng(seed)
    rows = []
    while len(rows) < 4:
        d = rng.uniform(50, 75)
        x, y = rng.uniform(60, 200), rng.uniform(60, 180)
        if all(np.hypot(x - a, y - b) * ETA >= (d + c) / 2 + 8 for a, b, c in rows):
            rows.append((x, y, d))
    design = load_design(write_design(tmp_path / "r.json", [
        patch(f"p{i}", x, y, d, 0.8) for i, (x, y, d) in enumerate(rows)], hoop="SQ14b"))
    pairs = [v.patches for v in check_design(design) if v.rule == "frame-conflict"]
    used, disjoint = set(), 0
    for a, b in pairs:
        if a not in used and b not in used:
            used |= {a, b}
            disjoint += 1
    assert _conflicts(design) >= disjoint
    assert disjoint == (0 if seed == 0 else 1)
