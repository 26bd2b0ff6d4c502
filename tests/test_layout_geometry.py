import math

import numpy as np
import pytest

from stitchswitch.errors import InvalidInputError
from stitchswitch.layout.embroidery import tessellation as tess
from stitchswitch.layout.embroidery.patch_geometry import ByAnnulus, ByIndex, ByPolygon, ByRing, make_patch


@pytest.mark.parametrize("diameter", [15.0, 40.0, 73.0, 100.0])
@pytest.mark.parametrize("resolution", [2.0, 3.3, 5.0, 8.0])
@pytest.mark.parametrize("fill", [0.3, 0.6, 0.8, 1.0])
def test_fill_within_one_percent_for_any_resolution(diameter, resolution, fill):
    g = make_patch(diameter, fill, resolution)
    # the exact areas and the stitched polygons (arcs as chords) both give p within 1 %
    assert abs(g.achieved_fill / fill - 1) < 0.01
    poly_area = sum(tess.polygon_area(p) for p in g.pieces_mm)
    assert abs(poly_area / g.patch_area_mm2 / fill - 1) < 0.01


def test_interior_triangles_are_equilateral_scaled_by_sqrt_p():
    g = make_patch(60.0, 0.64, 5.0)
    interior = [p for p in g.pieces_mm if len(p) == 3
                and np.all(np.hypot(p[:, 0], p[:, 1]) < 29.0)]
    assert len(interior) > 50
    for p in interior:
        sides = np.linalg.norm(p - np.roll(p, -1, axis=0), axis=1)
        np.testing.assert_allclose(sides, g.scale * 5.0, rtol=1e-9)
    # the global correction for the cut triangles keeps s close to sqrt(p)
    assert abs(g.scale - math.sqrt(0.64)) < 0.02


def test_pieces_stay_inside_circle_and_are_convex_ccw():
    g = make_patch(30.0, 0.9, 4.0)
    for p in g.pieces_mm:
        assert np.all(np.hypot(p[:, 0], p[:, 1]) <= 15.0 + 1e-9)
        e = np.roll(p, -1, axis=0) - p
        cross = e[:, 0] * np.roll(e[:, 1], -1) - e[:, 1] * np.roll(e[:, 0], -1)
        assert np.all(cross >= -1e-9)


def test_overlap_area_matches_clipped_polygon():
    tris = tess.lattice_triangles(10.0, 3.0)
    exact = tess.disk_overlap_area(tris, 10.0)
    clipped = [tess.polygon_area(tess.clip_to_disk(t, 10.0, 0.01)) if len(
        tess.clip_to_disk(t, 10.0, 0.01)) else 0.0 for t in tris]
    np.testing.assert_allclose(clipped, exact, atol=1e-4)
    assert exact.sum() == pytest.approx(math.pi * 100.0, rel=1e-12)


def test_deterministic():
    a, b = make_patch(40.0, 0.7, 4.0), make_patch(40.0, 0.7, 4.0)
    assert a.scale == b.scale
    assert all(np.array_equal(p, q) for p, q in zip(a.pieces_mm, b.pieces_mm))


def test_conductive_selections():
    g0 = make_patch(40.0, 0.8, 5.0)
    c = g0.centroids_mm
    r = np.hypot(c[:, 0], c[:, 1])
    g = make_patch(40.0, 0.8, 5.0, conductive=ByIndex((0, 3)))
    assert np.flatnonzero(g.conductive).tolist() == [0, 3]
    g = make_patch(40.0, 0.8, 5.0, conductive=ByRing((0,)))
    assert g.conductive.sum() == 6           # the hexagon of six triangles round the centre
    np.testing.assert_array_equal(g.conductive, r < 5.0 * math.sqrt(3) / 2)
    g = make_patch(40.0, 0.8, 5.0, conductive=ByAnnulus(8.0, 14.0))
    np.testing.assert_array_equal(g.conductive, (r >= 8.0) & (r < 14.0))
    g = make_patch(40.0, 0.8, 5.0, conductive=ByPolygon(((0.1, 0.1), (30, 0.1), (30, 30), (0.1, 30))))
    np.testing.assert_array_equal(g.conductive, (c[:, 0] > 0.1) & (c[:, 1] > 0.1))
    # the selection does not change the geometry
    assert g.scale == g0.scale


@pytest.mark.parametrize("kwargs", [dict(diameter_mm=float("nan"), fill=0.5),
                                    dict(diameter_mm=40.0, fill=0.0),
                                    dict(diameter_mm=40.0, fill=1.2),
                                    dict(diameter_mm=40.0, fill=0.5, resolution_mm=0.1)])
def test_bad_input(kwargs):
    with pytest.raises(InvalidInputError):
        make_patch(**kwargs)


def test_bad_index():
    with pytest.raises(InvalidInputError, match="index 999"):
        make_patch(40.0, 0.8, 5.0, conductive=ByIndex((999,)))
