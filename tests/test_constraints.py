"""The constraint check: one design per rule violating exactly that rule, the measured values,
and the feature-size formula against the generated stitch geometry."""
import math

import numpy as np
import pytest
import shapely

from stitchswitch.errors import InvalidInputError
from stitchswitch.layout.check.constraints import CheckLimits, Violation, check_design
from stitchswitch.layout.check.rules.features import feature_sizes
from stitchswitch.layout.embroidery.patch_design import geometry_for
from stitchswitch.layout.garment.design import CompositeSpec, Design, MachineSpec, PatchSpec, PieceSpec

ETA = 1.7        # the default material's pre-stretch


def design(*patches, hoop=None, outline=((0, 0), (300, 0), (300, 200), (0, 200)),
           blank=100.0) -> Design:
    """A one-piece design; hooped as a wide uncut blank (``blank`` mm) so that only the rule
    under test fires (a cut 300 x 200 mm piece leaves no room for a frame near its edges)."""
    return Design(1, [PieceSpec("panel", "", "test", outline)], list(patches),
                  machine=MachineSpec("janome-550e", hoop), blank_margin_mm=blank)


def patch(pid="a", centre=(150, 100), d=40.0, fill=1.0, **kw) -> PatchSpec:
    return PatchSpec(pid, "panel", centre, d, fill, **kw)


def rules(found) -> list[str]:
    return [v.rule for v in found]


def test_clean_design_has_no_violation():
    d = design(patch("a", (100, 100)), patch("b", (200, 100)), patch("c", (150, 150), 30, 0.4))
    assert check_design(d) == []


@pytest.mark.parametrize("centre,expected", [
    ((150, 25.0), 25.0 - 20 / ETA),          # inside, but closer than 15 mm to the edge
    ((150, 5.0), 5.0 - 20 / ETA),            # the footprint crosses the outline
    ((150, -10.0), -10.0 - 20 / ETA),        # the centre is outside the piece
])
def test_piece_edge(centre, expected):
    found = check_design(design(patch("a", centre)))
    assert rules(found) == ["piece-edge"]
    v = found[0]
    assert v.severity == "error" and v.patches == ("a",) and v.pieces == ("panel",)
    assert v.value == pytest.approx(expected) and v.limit == 15.0


def test_piece_edge_uses_the_relaxed_footprint_d_over_2_eta():
    r = 40 / (2 * ETA)
    just_in = design(patch("a", (150, 15.0 + r + 0.01)))
    just_out = design(patch("a", (150, 15.0 + r - 0.01)))
    assert check_design(just_in) == []
    assert rules(check_design(just_out)) == ["piece-edge"]
    relaxed = CheckLimits(seam_allowance_mm=0.0, edge_clearance_mm=0.0)
    assert check_design(design(patch("a", (150, r + 0.01))), relaxed) == []


def test_piece_edge_on_an_l_shaped_piece():
    ell = ((0, 0), (200, 0), (200, 100), (100, 100), (100, 200), (0, 200))
    ok = design(patch("a", (50, 50)), outline=ell)
    notch = design(patch("a", (150, 150)), outline=ell)      # in the bounding box, not the piece
    assert check_design(ok) == []
    (v,) = check_design(notch)
    assert v.rule == "piece-edge" and "outside the piece" in v.message


@pytest.mark.parametrize("dx,expected", [(40 / ETA + 2.0, 2.0), (40 / ETA - 3.0, -3.0)])
def test_spacing(dx, expected):
    d = design(patch("a", (100, 100)), patch("b", (100 + dx, 100)), patch("c", (250, 100)))
    found = check_design(d)
    assert rules(found) == ["spacing"]
    assert found[0].patches == ("a", "b") and found[0].value == pytest.approx(expected)
    assert ("overlap" in found[0].message) == (expected < 0)


def test_spacing_only_within_a_piece():
    pieces = [PieceSpec(n, "", "t", [[0, 0], [300, 0], [300, 200], [0, 200]]) for n in ("f", "b")]
    d = Design(1, pieces, [PatchSpec("a", "f", (100, 100), 40, 1.0),
                           PatchSpec("b", "b", (100, 100), 40, 1.0)])
    assert check_design(d) == []


def test_feature_side():
    found = check_design(design(patch(fill=0.1)))
    assert rules(found) == ["feature-side"]
    assert found[0].severity == "error" and found[0].value < 2.0 and found[0].limit == 2.0


def test_feature_gap():
    found = check_design(design(patch(fill=0.9)))
    assert rules(found) == ["feature-gap"]
    v = found[0]
    assert v.severity == "warning" and v.value == pytest.approx(0.15, abs=0.01) and v.limit == 0.3
    assert check_design(design(patch(fill=0.8))) == []                   # 0.30 mm gaps: fine
    assert check_design(design(patch(fill=0.9)), CheckLimits(min_gap_mm=0.1)) == []
    assert check_design(design(patch(fill=0.9)), CheckLimits(resolution_mm=20.0)) == []
    assert rules(check_design(design(patch(fill=0.8)), CheckLimits(min_gap_mm=1.0))) == ["feature-gap"]


def test_hoop_fit_largest_and_chosen_hoop():
    big = design(patch("a", (150, 100), d=195.0))           # RE36b: 200 mm, 5 mm margin
    assert rules(check_design(big)) == ["model-range", "hoop-fit"]
    v = check_design(big)[1]
    assert v.value == pytest.approx(205.0) and v.limit == 200.0
    assert rules(check_design(design(patch("a", (150, 100), d=190.0)))) == ["model-range"]
    small_hoop = design(patch("a", (150, 100), d=135.0), hoop="SQ14b")
    assert rules(check_design(small_hoop)) == ["hoop-fit"]
    assert check_design(small_hoop, CheckLimits(hoop_margin_mm=2.0)) == []


def test_geometry_rule_reports_what_cannot_be_tessellated():
    found = check_design(design(patch(conductive="index:9999")))
    assert rules(found) == ["geometry"]
    assert "9999" in found[0].message and math.isnan(found[0].value)


def test_violation_record():
    (v,) = check_design(design(patch(fill=0.9)))
    assert isinstance(v, Violation)
    d = v.as_dict()
    assert list(d) == ["rule", "severity", "patches", "pieces", "value", "limit", "message",
                       "hint"]
    assert d["patches"] == ["a"]


@pytest.mark.parametrize("field,value,message", [
    ("min_gap_mm", -1.0, "min_gap_mm: -1.0 must be >= 0"),
    ("seam_allowance_mm", float("inf"), "seam_allowance_mm: inf is not a finite number"),
    ("resolution_mm", 0.0, "resolution_mm: 0.0 must be > 0"),
])
def test_limits_are_validated(field, value, message):
    with pytest.raises(InvalidInputError, match=message):
        CheckLimits(**{field: value})


# --- the feature-size formula, measured on the generated pieces -----------------------------

def _interior(geom):
    """Interior pieces (whole scaled triangles): 3 vertices, well inside the circle."""
    r = geom.diameter_mm / 2 - geom.resolution_mm
    return [p for p in geom.pieces_mm
            if len(p) == 3 and np.hypot(*p.mean(axis=0)) < r]


def _measured(pieces):
    polys = [shapely.Polygon(p) for p in pieces]
    tree = shapely.STRtree(polys)
    best = math.inf
    for i, poly in enumerate(polys):
        for j in tree.query(poly.buffer(3.0)):
            if j != i:
                best = min(best, poly.distance(polys[j]))
    sides = [np.hypot(*np.diff(np.vstack([p, p[:1]]), axis=0).T).min() for p in pieces]
    return min(sides), best


@pytest.mark.parametrize("fill,resolution", [(0.5, 5.0), (0.8, 5.0), (0.3, 4.0)])
def test_gap_and_side_formula_match_the_geometry(fill, resolution):
    geom = geometry_for(patch(d=40, fill=fill), resolution)
    side, gap = feature_sizes(geom)
    assert gap == pytest.approx((1 - geom.scale) * resolution / math.sqrt(3), rel=1e-9)
    m_side, m_gap = _measured(_interior(geom))
    assert side == pytest.approx(m_side, rel=1e-6)
    assert gap == pytest.approx(m_gap, rel=1e-6)


def test_composite_gap_is_the_smallest_over_region_pairs():
    spec = patch(d=60, fill=0.4, composite=CompositeSpec(30.0, 0.9))
    geom = geometry_for(spec, 5.0)
    s = np.unique(np.round(geom.piece_scale, 12))
    assert len(s) == 2
    side, gap = feature_sizes(geom)
    a = 5.0
    assert side == pytest.approx(s.min() * a)
    within_core = (1 - s.max()) * a / math.sqrt(3)
    assert gap == pytest.approx(within_core)               # the core's own gap is the smallest
    # measured: the closest two interior pieces anywhere (core, surround or across) are that far
    m_side, m_gap = _measured(_interior(geom))
    assert m_gap == pytest.approx(gap, rel=1e-6) and m_side == pytest.approx(side, rel=1e-6)
    # across the boundary the gap is the mean of the two regions' gaps
    across = (2 - s[0] - s[1]) * a / (2 * math.sqrt(3))
    assert within_core < across < (1 - s.min()) * a / math.sqrt(3)
