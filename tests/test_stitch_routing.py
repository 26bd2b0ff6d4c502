"""The thread's route: electrodes sewn as one conductor (checked on the decoded JEF file, with a
union-find written here, not the audit's), crossings at the narrowest, centre outward, the
travel choice, and the hygiene rules on the sewn records."""
import math

import numpy as np
import pytest
import shapely

from stitchswitch.layout.embroidery import export
from stitchswitch.layout.embroidery import stitches as st
from stitchswitch.layout.embroidery.patch_geometry import make_patch, parse_selection
from stitchswitch.layout.embroidery.sewing import routing
from stitchswitch.layout.embroidery.sewing.audit import audit

from decoders import dst, jef


def _find(parent, i):
    while parent[i] != i:
        parent[i] = parent[parent[i]]
        i = parent[i]
    return i


def _electrode_threads(data: bytes, pieces) -> int:
    """Connected thread components, in the decoded conductive block (after the colour change),
    among the needle holes that lie in ``pieces``; a TRIM cuts the thread."""
    d = jef.decode(data)
    after = [k for k, r in enumerate(d.records) if r[0] == dst.COLOR][0]
    holes, parent, prev = {}, [], None

    def node(x, y):
        if (x, y) not in holes:
            holes[(x, y)] = len(parent)
            parent.append(len(parent))
        return holes[(x, y)]

    for c, x, y in d.records[after + 1:]:
        if c == jef.TRIM or c == dst.END:
            prev = None
            continue
        if c == dst.STITCH:
            n = node(x, y)
            if prev is not None:
                parent[_find(parent, n)] = _find(parent, prev)
            prev = n
        elif c == dst.JUMP and prev is not None:
            n = node(x, y)                       # a float: the thread is not cut
            parent[_find(parent, n)] = _find(parent, prev)
            prev = n
    area = shapely.union_all([shapely.Polygon(p) for p in pieces]).buffer(0.15)
    inside = [i for (x, y), i in holes.items() if area.covers(shapely.Point(x / 10, y / 10))]
    return len({_find(parent, i) for i in inside})


@pytest.mark.parametrize("d, p, res, selection", [
    (51.0, 0.7198, 5.0, "ring:0"), (40.0, 0.3, 5.0, "ring:0,1"), (40.0, 0.6, 5.0, "ring:0,1"),
    (40.0, 0.6, 2.0, "ring:0,1"), (60.0, 0.6, 5.0, "annulus:10:16")])
def test_every_electrode_is_one_thread_in_the_decoded_file(d, p, res, selection):
    geom = make_patch(d, p, res, parse_selection(selection))
    plan = st.plan_stitches(geom)
    data = export.encode(plan, "jef")
    regions = routing.electrode_regions(geom.centroids_mm, geom.conductive, res)
    assert len(regions) == 1
    assert _electrode_threads(data, [geom.pieces_mm[i] for i in regions[0]]) == 1


def test_two_electrodes_are_two_threads_never_joined():
    geom = make_patch(60.0, 0.6, 5.0, parse_selection("ring:0,4"))
    plan = st.plan_stitches(geom)
    regions = routing.electrode_regions(geom.centroids_mm, geom.conductive, 5.0)
    assert len(regions) == 2
    a = audit(plan, geom.pieces_mm, geom.conductive, geom.centroids_mm, 5.0)
    assert a.electrode_components == (1, 1)
    data = export.encode(plan, "jef")
    every = [geom.pieces_mm[i] for r in regions for i in r]
    assert _electrode_threads(data, every) == 2


def test_crossings_go_across_the_narrowest_gap():
    geom = make_patch(40.0, 0.6, 5.0)
    gap = (1 - geom.scale) * 5.0 / math.sqrt(3)          # between edge neighbours
    a = audit(st.plan_stitches(geom), geom.pieces_mm, geom.conductive, geom.centroids_mm, 5.0)
    assert a.gap_crossings > 0
    # each crossing is one gap wide (within the 0.1 mm grid), almost all between edge neighbours
    assert a.gap_crossing_mm / a.gap_crossings <= 1.15 * gap + 0.1


def test_crossings_plus_trims_cover_every_move():
    """Each piece is an island: every move between pieces crosses a gap or is trimmed."""
    geom = make_patch(40.0, 0.3, 5.0)
    n = geom.n_triangles
    for travel in st.TRAVELS:
        plan = st.plan_stitches(geom, st.StitchParams(travel=travel))
        a = audit(plan, geom.pieces_mm, geom.conductive, geom.centroids_mm, 5.0)
        assert a.gap_crossings + a.trims >= n - 1
        if travel == "trim":
            assert a.gap_crossings == 0 and a.trims == n
        if travel == "jump":
            assert plan.jump_count > plan.trim_count        # floats: jumps without a trim


def test_route_starts_at_the_centre_and_goes_outward():
    geom = make_patch(60.0, 0.6, 5.0)
    steps = routing.route(geom.pieces_mm, geom.centroids_mm, (0, 0), 5.0, 2.5)
    order = [s.piece for s in steps]
    assert sorted(order) == list(range(geom.n_triangles))
    r = np.hypot(*geom.centroids_mm[order].T)
    assert r[0] == r.min()
    assert np.corrcoef(np.arange(len(r)), r)[0, 1] > 0.7
    # fewer restarts (trims) than a tenth of the pieces
    assert sum(s.kind == routing.RESTART for s in steps) < geom.n_triangles / 10


def test_a_gap_in_an_electrode_is_bridged_not_trimmed():
    """Three pieces in a row, the middle one far enough that the walk gets stuck at an end:
    the route bridges back through the stitched pieces."""
    tri = np.array([[0.0, 0.0], [2.0, 0.0], [1.0, 1.7]])
    pieces = [tri, tri + [2.4, 0], tri + [4.8, 0], tri + [7.2, 0]]
    cent = np.array([p.mean(axis=0) for p in pieces])
    steps = routing.route(pieces, cent, cent[1], 2.4, 1.0, [np.arange(4)])
    assert steps[0].piece == 1
    assert [s.kind for s in steps[1:]].count(routing.RESTART) == 0
    assert any(s.kind == routing.BRIDGE for s in steps)


def test_no_short_stitch_and_ties_of_at_least_three_stitches_on_fine_lattices():
    geom = make_patch(40.0, 0.6, 2.0, parse_selection("ring:0,1"))
    plan = st.plan_stitches(geom)
    a = audit(plan, geom.pieces_mm, geom.conductive, geom.centroids_mm, 2.0)
    assert a.short_stitches == 0
    assert a.min_tie_stitches >= 3 and a.min_tie_stitch_mm >= 0.5 - 1e-9


def test_pull_compensation_stays_within_a_quarter_of_the_gap():
    geom = make_patch(40.0, 0.6, 2.0)
    gap = (1 - geom.scale) * 2.0 / math.sqrt(3)
    plan = st.plan_stitches(geom, st.StitchParams(underlay=False, travel="trim"))
    fill = plan.xy_mm[(plan.commands == st.STITCH) & ~plan.ties]
    stitched = shapely.union_all([shapely.Polygon(p) for p in geom.pieces_mm])
    out = shapely.distance(shapely.points(fill), stitched)
    assert out.max() <= 0.25 * gap + 0.071          # + the 0.1 mm grid
    assert out.max() > 0.25 * gap - 0.071            # the compensation is applied


def test_small_pieces_are_warned_about():
    plan = st.plan_stitches(make_patch(100.0, 0.6, 5.0))
    assert plan.small_pieces > 0
    assert any("warning" in n and "mm^2" in n for n in plan.fabrication_notes())


def test_bobbin_note_says_when_the_normal_bobbin_comes_back():
    plan = st.plan_stitches(make_patch(40.0, 0.6, 5.0, parse_selection("ring:0")))
    note = [n for n in plan.fabrication_notes() if "bobbin" in n][0]
    assert "conductive bobbin in" in note and "normal bobbin back" in note


def test_bad_travel_and_lock():
    from stitchswitch.errors import InvalidInputError
    with pytest.raises(InvalidInputError, match="travel 'hop'"):
        st.StitchParams(travel="hop")
    with pytest.raises(InvalidInputError, match="lock_stitches"):
        st.StitchParams(lock_stitches=2)


def test_conductive_pieces_planned_alone_as_fabrication_does_stay_one_thread():
    """Fabrication plans a patch's conductive pieces as a block of their own (no conductive
    mask): each lattice-connected group is still one thread."""
    from stitchswitch.layout.fabrication.plan import _subset
    geom = make_patch(40.0, 0.3, 5.0, parse_selection("ring:0,1"))
    sub = _subset(geom, geom.conductive)
    plan = st.plan_stitches(sub, st.StitchParams(), (30.0, -10.0))
    assert plan.trim_count == 1
    a = audit(plan, [p + [30.0, -10.0] for p in sub.pieces_mm], np.ones(sub.n_triangles, bool),
              sub.centroids_mm + [30.0, -10.0], 5.0)
    assert a.trims == 1 and a.gap_crossings >= sub.n_triangles - 1
