
import numpy as np
import pyembroidery as pe
import pytest

from stitchswitch.errors import InvalidInputError
from stitchswitch.layout.embroidery import export
from stitchswitch.layout.embroidery import stitch_preview as preview
from stitchswitch.layout.embroidery import stitches as st
from stitchswitch.layout.embroidery.machines import default_machine
from stitchswitch.layout.embroidery.patch_geometry import ByRing, make_patch

from decoders import dst, jef
from helpers import EXTERNAL

STAR = EXTERNAL / "embroidery"


@pytest.fixture(scope="module")
def plan():
    return st.plan_stitches(make_patch(40.0, 0.8, 5.0, conductive=ByRing((0, 1))))


@pytest.fixture(scope="module")
def long_jump_plan():
    """Two far-apart pieces: a 60 mm jump that every byte format must split."""
    from stitchswitch.layout.embroidery.sewing.runs import Builder
    tri = np.array([[0.0, 0.0], [5.0, 0.0], [2.5, 4.33]])
    prm = st.StitchParams()
    b = Builder(prm)
    b.extend(st.fill_piece(tri, prm), tri)
    b.end_run()
    b.extend(st.fill_piece(tri + [60.0, 0.0], prm), tri + [60.0, 0.0])
    b.finish((0.0, 0.0))
    return st.StitchPlan(np.asarray(b.xy), np.asarray(b.cmd, dtype=np.int8),
                         (st.NORMAL_THREAD,))


def test_registry():
    assert export.supported_formats() == ["dst", "exp", "jef", "pes", "vp3"]
    with pytest.raises(InvalidInputError, match="supported: dst, exp, jef, pes, vp3"):
        export.get_format("xxx")
    assert export.format_from_path("a/b.JEF").name == "jef"


def _check(decoded, plan, max_move):
    planned = plan.xy_mm[plan.commands == st.STITCH]
    assert decoded.count(dst.STITCH) == len(planned)
    x0, y0, x1, y1 = decoded.extents()
    ex = planned.min(axis=0), planned.max(axis=0)
    np.testing.assert_allclose([x0 / 10, y0 / 10], ex[0], atol=0.1 + 1e-9)
    np.testing.assert_allclose([x1 / 10, y1 / 10], ex[1], atol=0.1 + 1e-9)
    for dx, dy in decoded.moves((dst.STITCH, dst.JUMP)):
        assert max(abs(dx), abs(dy)) <= max_move          # the formats' limit is per axis
    assert decoded.records[-1][0] == dst.END


@pytest.mark.parametrize("which", ["plan", "long_jump_plan"])
def test_dst_decodes_independently(which, request):
    p = request.getfixturevalue(which)
    d = dst.decode(export.encode(p, "dst"))
    _check(d, p, dst.MAX_MOVE)
    assert d.count(dst.COLOR) == p.color_changes


@pytest.mark.parametrize("which", ["plan", "long_jump_plan"])
def test_jef_decodes_independently(which, request):
    p = request.getfixturevalue(which)
    d = jef.decode(export.encode(p, "jef", default_machine().hoops[0]))
    _check(d, p, jef.MAX_MOVE)
    assert d.count(dst.COLOR) == p.color_changes
    assert d.count(jef.TRIM) == p.trim_count          # the Janome trims are kept
    assert d.header["hoop"] == 2 and d.header["date"] == export.JEF_FIXED_DATE


def test_long_jump_is_split_not_truncated(long_jump_plan):
    assert long_jump_plan.jump_count == 1 or long_jump_plan.jump_count == 2
    d = dst.decode(export.encode(long_jump_plan, "dst"))
    jumps = [m for m, r in zip(d.moves((dst.STITCH, dst.JUMP, dst.COLOR)), d.records)
             if r[0] == dst.JUMP]
    assert sum(1 for dx, dy in jumps if abs(dx) > 100) >= 5      # 60 mm in >= 5 jumps


def test_jef_hoop_code_follows_chosen_hoop(plan):
    codes = {h.name: jef.decode(export.encode(plan, "jef", h)).header["hoop"]
             for h in default_machine().hoops[:3]}
    assert codes == {"SQ14b": 2, "RE20b": 2, "SQ20b": 4}


@pytest.mark.parametrize("fmt", ["dst", "exp", "jef", "pes", "vp3"])
def test_every_format_round_trips_through_pyembroidery(plan, fmt, tmp_path):
    path = tmp_path / f"patch.{fmt}"
    export.write(path, plan)
    assert path.read_bytes() == export.encode(plan, fmt)      # byte-identical, deterministic
    back = pe.read(str(path))
    n = sum(1 for s in back.stitches if s[2] == pe.STITCH)
    assert n == plan.stitch_count
    x0, y0, x1, y1 = back.bounds()
    e = plan.extents_mm()
    assert (x1 - x0) / 10 == pytest.approx(e[2] - e[0], abs=0.15)
    assert [p.name for p in tmp_path.iterdir()] == [f"patch.{fmt}"]   # no temp file left


@pytest.mark.parametrize("name,mod", [("Star.DST", dst), ("Star.JEF", jef)])
def test_decoders_agree_with_pyembroidery_on_external_star(name, mod):
    d = mod.decode((STAR / name).read_bytes())
    p = pe.read(str(STAR / name))
    assert d.count(dst.STITCH) == sum(1 for s in p.stitches if s[2] == pe.STITCH)
    x0, y0, x1, y1 = d.extents((dst.STITCH, dst.JUMP))
    assert ((x1 - x0) / 10, (y1 - y0) / 10) == (pytest.approx(59.1), pytest.approx(62.3))
    b = p.bounds()
    assert (x1 - x0, y1 - y0) == (b[2] - b[0], b[3] - b[1])


def test_hoop_choice():
    assert default_machine().choose_hoop(130, 130).name == "SQ14b"
    assert default_machine().choose_hoop(130, 190).name == "RE20b"
    assert default_machine().choose_hoop(190, 300).name == "RE36b"
    with pytest.raises(InvalidInputError, match="largest is RE36b 200 x 360 mm"):
        default_machine().choose_hoop(220, 220)


@pytest.mark.parametrize("fmt", ["png", "svg"])
def test_preview(plan, fmt, tmp_path):
    path = tmp_path / f"plan.{fmt}"
    preview.write_preview(path, plan, 40.0)
    data = path.read_bytes()
    assert data.startswith(b"\x89PNG") if fmt == "png" else b"<svg" in data[:2000]
    if fmt == "svg":
        assert data == preview.render(plan, "svg", 40.0)
        assert b"stroke-dasharray" in data          # the jumps


def _signed_bounds(decoded):
    x0, y0, x1, y1 = decoded.extents()
    return x0, y0, x1, y1


@pytest.mark.parametrize("centre", [(0.0, 0.0), (35.0, -20.0)])
def test_headers_hold_the_real_bounds_about_the_hoop_centre(centre):
    """JEF left/top/right/bottom and DST +X/-X/+Y/-Y are the signed distances of the stitch
    bounds from the hoop centre, decoded independently (an off-centre patch: nothing left of
    the centre, so -X is negative)."""
    import struct
    p = st.plan_stitches(make_patch(30.0, 0.6, 5.0), center_mm=centre)
    hoop = default_machine().hoop("RE20b")
    data = export.encode(p, "jef", hoop)
    x0, y0, x1, y1 = _signed_bounds(jef.decode(data))
    assert struct.unpack_from("<4i", data, 36) == (-x0, y1, x1, -y0)
    d = dst.decode(export.encode(p, "dst", label="button firm 1"))
    x0, y0, x1, y1 = _signed_bounds(d)
    assert [int(d.header[k]) for k in ("+X", "-X", "+Y", "-Y")] == [x1, -x0, y1, -y0]
    assert d.header["LA"] == "button firm 1"
    if centre[0] > 15:
        assert int(d.header["-X"]) < 0


def test_hoop_without_a_published_code_gets_the_smallest_field_holding_the_design():
    from stitchswitch.layout.embroidery.hoop_spec import Hoop, jef_code_for
    big = Hoop("RE36b", 200, 360, None)
    assert jef_code_for(big, (-20, -20, 20, 20)) == (1, False)        # 50 x 50
    assert jef_code_for(big, (-20, -20, 60, 20)) == (3, False)        # 120 wide: 126 x 110
    assert jef_code_for(big, (-90, -150, 90, 150)) == (4, False)      # none holds it: 200x200
    assert jef_code_for(default_machine().hoop("SQ14b"), (0, 0, 1, 1)) == (2, True)
