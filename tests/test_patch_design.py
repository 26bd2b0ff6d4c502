"""Composite and non-circular patches (layout.embroidery.patch_design): per-region fill, plain-case identity,
convex pieces, conductive selection and stitchability."""
from types import SimpleNamespace as NS

import numpy as np
import pytest
import shapely

from stitchswitch.errors import InvalidInputError
from stitchswitch.layout.embroidery import tessellation as tess
from stitchswitch.layout.embroidery.patch_design import geometry_for
from stitchswitch.layout.embroidery.patch_geometry import make_patch
from stitchswitch.layout.embroidery.stitches import plan_stitches


def spec(d=60.0, p=0.5, core=None, outline=None, conductive=None):
    comp = None if core is None else NS(core_diameter_mm=core[0], core_fill=core[1])
    return NS(id="t", diameter_mm=d, fill=p, composite=comp, outline_mm=outline,
              conductive=conductive)


def star(r_out=29.0, r_in=18.0, n=5):
    ang = np.linspace(0, 2 * np.pi, 2 * n + 1)[:-1]
    rr = np.where(np.arange(2 * n) % 2 == 0, r_out, r_in)
    return np.column_stack([rr * np.cos(ang), rr * np.sin(ang)])


def core_cells_area(d, core_d, res, boundary=None):
    tris = tess.lattice_triangles(d / 2, res)
    c = tris.mean(axis=1)
    cells = tris[np.hypot(c[:, 0], c[:, 1]) < core_d / 2]
    if boundary is None:
        return float(tess.disk_overlap_area(cells, d / 2).sum())
    return float(shapely.area(shapely.intersection(shapely.polygons(cells), boundary)).sum())


def region_fills(g, core_d, res, boundary=None):
    core = np.hypot(g.centroids_mm[:, 0], g.centroids_mm[:, 1]) < core_d / 2
    ca = core_cells_area(g.diameter_mm, core_d, res, boundary)
    return g.areas_mm2[core].sum() / ca, g.areas_mm2[~core].sum() / (g.patch_area_mm2 - ca)


def test_plain_spec_is_the_circular_patch():
    g = geometry_for(spec(40, 0.8, conductive="ring:0"))
    ref = make_patch(40, 0.8, 5.0)
    assert g.n_triangles == ref.n_triangles
    assert g.achieved_fill == pytest.approx(0.8, rel=1e-9)
    assert g.conductive.sum() > 0


@pytest.mark.parametrize("res", [3.0, 5.0])
@pytest.mark.parametrize("fills", [(0.5, 1.0), (0.6, 0.9), (0.3, 0.7)])
def test_composite_region_fills(res, fills):
    p, core_fill = fills
    g = geometry_for(spec(60, p, core=(24, core_fill)), res)
    f_core, f_out = region_fills(g, 24, res)
    assert f_core == pytest.approx(core_fill, rel=1e-3)
    assert f_out == pytest.approx(p, rel=1e-3)
    # the core is stitched denser than the surround
    core = np.hypot(*g.centroids_mm.T) < 12
    assert g.piece_scale[core].min() > g.piece_scale[~core].max()


def test_star_outline_fills_and_convex_pieces():
    outline = star()
    boundary = shapely.Polygon(outline)
    g = geometry_for(spec(60, 0.5, core=(20, 1.0), outline=outline), 5.0)
    f_core, f_out = region_fills(g, 20, 5.0, boundary)
    assert f_core == pytest.approx(1.0, rel=1e-9)
    assert f_out == pytest.approx(0.5, rel=1e-6)
    assert g.patch_area_mm2 == pytest.approx(boundary.area)
    for piece in g.pieces_mm:
        poly = shapely.Polygon(piece)
        assert poly.area == pytest.approx(poly.convex_hull.area, rel=1e-6)   # convex
        assert tess.polygon_area(piece) > 0                                  # CCW
        assert boundary.buffer(1e-6).contains(poly)                          # inside the outline


def test_composite_patch_stitches():
    g = geometry_for(spec(50, 0.6, core=(20, 1.0), outline=star(24, 16), conductive="ring:0"))
    plan = plan_stitches(g)
    assert plan.stitch_count > 500
    assert len(plan.threads) == 2


def test_core_without_triangles_is_an_error():
    with pytest.raises(InvalidInputError, match="core"):
        geometry_for(spec(60, 0.5, core=(0.5, 1.0)), 5.0)


def test_self_intersecting_outline_is_an_error():
    bow = np.array([[-20, -20], [20, 20], [20, -20], [-20, 20]], dtype=float)
    with pytest.raises(InvalidInputError, match="outline"):
        geometry_for(spec(60, 0.5, core=(10, 1.0), outline=bow))


@pytest.mark.parametrize("core", [None, (20.0, 1.0)])
def test_a_conductive_selection_that_selects_nothing_is_an_error(core):
    with pytest.raises(InvalidInputError, match="conductive 'ring:99' selects no triangle"):
        geometry_for(spec(core=core, conductive="ring:99"), 5.0)
    assert geometry_for(spec(core=core, conductive="ring:0"), 5.0).conductive.any()


def test_the_check_and_fabricate_refuse_an_empty_conductive_selection(tmp_path):
    import json

    from helpers import cli_run

    obj = {"version": 1, "pieces": [{"name": "front", "outline_mm": [[0, 0], [200, 0],
                                                                    [200, 150], [0, 150]]}],
           "patches": [{"id": "a", "piece": "front", "centre_mm": [60, 60], "diameter_mm": 24,
                        "fill": 0.8, "conductive": "ring:99"}]}
    path = tmp_path / "d.json"
    path.write_text(json.dumps(obj))
    r = cli_run("check", path)
    assert r.exit_code == 1 and "conductive 'ring:99' selects no triangle" in r.output
    r = cli_run("fabricate", path, "-o", tmp_path / "out")
    assert r.exit_code == 2 and not (tmp_path / "out").exists()
