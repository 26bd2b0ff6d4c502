"""``stitchswitch fabricate``: the output folder, its content against the plan, deterministic
bytes, refusal to overwrite, nothing left behind on errors."""
import json
import os

import pytest

from stitchswitch.errors import InvalidInputError
from stitchswitch.layout.embroidery.patch_design import geometry_for
from stitchswitch.layout.fabrication import fabricate as fab
from stitchswitch.layout.garment.design_io import load_design

from decoders import dst, jef
from helpers import cli_run as run


def patch(pid, x, y, d, p, conductive=None, top="#1b1b1b"):
    return {"id": pid, "piece": "front", "centre_mm": [x, y], "diameter_mm": d, "fill": p,
            "composite": None, "outline_mm": None, "conductive": conductive,
            "threads": {"top": top, "conductive": "#b0b0b0"}, "state": "up"}


def write_design(path, patches, size=(300, 250), hoop=None):
    w, h = size
    obj = {"version": 1,
           "pieces": [{"name": "front", "size": "M", "source": "test",
                       "outline_mm": [[0, 0], [w, 0], [w, h], [0, h]]}],
           "patches": patches, "material": {"name": "default"},
           "machine": {"name": "janome-550e", "hoop": hoop}}
    path.write_text(json.dumps(obj))
    return path


SMALL = [patch("a", 60, 60, 24, 0.8, "ring:0"), patch("b", 110, 70, 20, 0.7),
         patch("c", 230, 180, 24, 0.9, None, "#204080")]




def leftovers(folder):
    return sorted(n for n in os.listdir(folder) if n.startswith("."))


def test_garment_outputs_match_the_plan(tmp_path):
    design = write_design(tmp_path / "design.json", SMALL)
    out = tmp_path / "out"
    r = run("fabricate", design, "-o", out)
    assert r.exit_code == 0, r.output
    doc = json.loads((out / "fabrication.json").read_text())
    n = len(doc["hoopings"])
    assert n == doc["grouping"]["hoopings"] == 2 and doc["grouping"]["method"] == "mip"
    assert doc["grouping"]["optimal"] and doc["order"]["conflicts"] == []
    names = {f"hoop0{k}{e}" for k in range(1, n + 1)
             for e in (".jef", ".png", ".svg", "-template-a4.pdf", "-template-letter.pdf",
                       "-marks.dxf")}
    assert sorted(os.listdir(out)) == sorted(names | {"overview.png", "overview.svg",
                                                      "fabrication.json", "fabrication.md",
                                                      "fabrication.html"})
    ids = sorted(p["id"] for h in doc["hoopings"] for p in h["patches"])
    assert ids == ["a", "b", "c"]
    for h in doc["hoopings"]:
        d = jef.decode((out / h["files"]["embroidery"]).read_bytes())
        assert d.count(dst.STITCH) == h["stitches"]
        conductive = any(t["role"] == "conductive" for t in h["threads"])
        assert d.count(dst.COLOR) == h["colour_changes"] == len(h["threads"]) - 1
        assert conductive == any(p["id"] == "a" for p in h["patches"])
        x0, y0, x1, y1 = d.extents()
        assert max(abs(x0), abs(x1)) <= 10 * 70 and max(abs(y0), abs(y1)) <= 10 * 70  # SQ14b
        assert d.header["hoop"] == {"SQ14b": 2, "RE20b": 2, "SQ20b": 4}[h["hoop"]]
        assert (out / h["files"]["png"]).read_bytes().startswith(b"\x89PNG")
        assert b"<svg" in (out / h["files"]["svg"]).read_bytes()[:500]
    md = (out / "fabrication.md").read_text()
    assert "stretch it uniformly to 1.7x in both directions" in md
    assert ("conductive Pale Sky, Janome 216 (JEF colour 21, design colour #b0b0b0) "
            "(conductive thread in the bobbin") in md
    assert "860 stitches/min" in md
    page = (out / "fabrication.html").read_text()
    assert page.count("data:image/png;base64,") == n + 1 and "http" not in page.replace(
        "http-equiv", "")
    assert "hoopings    2" in r.output and "gap 0.00 %" in r.output
    assert leftovers(tmp_path) == []


def test_deterministic_bytes(tmp_path):
    design = write_design(tmp_path / "design.json", SMALL[:1])
    a, b = tmp_path / "a", tmp_path / "b"
    assert run("fabricate", design, "-o", a).exit_code == 0
    assert run("fabricate", design, "-o", b).exit_code == 0
    assert sorted(os.listdir(a)) == sorted(os.listdir(b))
    for name in os.listdir(a):
        assert (a / name).read_bytes() == (b / name).read_bytes(), name


def test_overwrite_rules(tmp_path):
    design = write_design(tmp_path / "design.json", SMALL[:1])
    out = tmp_path / "out"
    out.mkdir()                                       # an empty directory is fine
    assert run("fabricate", design, "-o", out).exit_code == 0
    first = (out / "hoop01.jef").read_bytes()
    r = run("fabricate", design, "-o", out)
    assert r.exit_code == 2 and r.output.startswith("Error: output directory")
    assert "is not empty" in r.output and len(r.output.strip().splitlines()) == 1
    (out / "hoop01.jef").write_bytes(b"old")
    (out / "stray.txt").write_text("x")
    r = run("fabricate", design, "-o", out, "--force")
    assert r.exit_code == 0, r.output
    assert (out / "hoop01.jef").read_bytes() == first and not (out / "stray.txt").exists()
    f = tmp_path / "file"
    f.write_text("x")
    r = run("fabricate", design, "-o", f)
    assert r.exit_code == 2 and "is a file" in r.output
    assert leftovers(tmp_path) == []


def test_free_mode_dst(tmp_path):
    design = write_design(tmp_path / "design.json", SMALL)
    out = tmp_path / "free"
    r = run("fabricate", design, "--mode", "free", "--format", "dst", "--spacing", "8", "-o", out)
    assert r.exit_code == 0, r.output
    doc = json.loads((out / "fabrication.json").read_text())
    assert doc["mode"] == "free" and doc["grouping"]["spacing_mm"] == 8
    assert len(doc["hoopings"]) == 1 and doc["hoopings"][0]["hoop"] == "SQ14b"
    d = dst.decode((out / "hoop01.dst").read_bytes())
    assert d.count(dst.STITCH) == doc["hoopings"][0]["stitches"]
    assert "sew it onto the garment" in (out / "fabrication.md").read_text()


@pytest.mark.parametrize("patches,args,message", [
    ([patch("big", 100, 100, 230, 0.8)], [],
     "patch 'big': its 230 mm footprint on the stretched fabric fits no hoop"),
    ([patch("edge", 12, 100, 20, 0.8)], [],
     "patch 'edge' cannot be hooped: it is too close to the edge of piece 'front'"),
    (SMALL, ["--format", "xyz"], "unsupported embroidery format 'xyz'"),
    (SMALL, ["--machine", "brother"], "unknown machine 'brother'"),
    (SMALL, ["--hoop", "XL"], "'XL' is not a hoop of the janome-550e"),
    (SMALL, ["--time-limit", "0"], "--time-limit 0 must be positive"),
])
def test_errors_leave_nothing(tmp_path, patches, args, message):
    design = write_design(tmp_path / "design.json", patches)
    out = tmp_path / "out"
    r = run("fabricate", design, "-o", out, *args)
    assert r.exit_code == 2, r.output
    assert r.output.startswith("Error: ") and message in r.output
    assert len(r.output.strip().splitlines()) == 1
    assert not out.exists() and leftovers(tmp_path) == []


def test_bad_machines_file(tmp_path):
    design = write_design(tmp_path / "design.json", SMALL)
    bad = tmp_path / "m.json"
    bad.write_text(json.dumps({"format": "stitchswitch machines", "version": 1, "machines": [
        {"name": "m", "label": "M", "stitches_per_minute": 600, "default_format": "dst",
         "hoops": [{"name": "H", "width_mm": 100, "height_mm": 100, "margin_mm": -1,
                    "frame_width_mm": 10, "jef_code": None}]}]}))
    r = run("fabricate", design, "--machines", bad, "--machine", "m", "-o", tmp_path / "out")
    assert r.exit_code == 2
    assert "machines[0].hoops[0].margin_mm: -1 must be >= 0" in r.output


def test_failure_midway_is_atomic(tmp_path):
    """A failure while building the files (here: the geometry of the last patch) leaves neither
    the output directory nor a temporary one, and an existing target is untouched."""
    design = load_design(write_design(tmp_path / "design.json", SMALL))

    def failing(spec):
        if spec.id == "c":
            raise InvalidInputError("patch c: no geometry")
        return geometry_for(spec)

    out = tmp_path / "out"
    with pytest.raises(InvalidInputError, match="no geometry"):
        fab.fabricate(design, out, fab.FabricateOptions(), geometry=failing)
    assert not out.exists() and leftovers(tmp_path) == []
    out.mkdir()
    (out / "keep.txt").write_text("mine")
    with pytest.raises(InvalidInputError, match="no geometry"):
        fab.fabricate(design, out, fab.FabricateOptions(force=True), geometry=failing)
    assert os.listdir(out) == ["keep.txt"] and leftovers(tmp_path) == []


def test_write_failure_is_atomic(tmp_path, monkeypatch):
    design = load_design(write_design(tmp_path / "design.json", SMALL[:1]))
    from stitchswitch.files import outdir as od
    calls = []

    def flaky(path, data):
        calls.append(path)
        if len(calls) == 3:
            raise OSError(28, "No space left on device", str(path))
        return real(path, data)

    real = od.atomic_write_bytes
    monkeypatch.setattr(od, "atomic_write_bytes", flaky)
    with pytest.raises(InvalidInputError, match="'.*out': cannot be written .No space left"):
        fab.fabricate(design, tmp_path / "out", fab.FabricateOptions())
    assert not (tmp_path / "out").exists() and leftovers(tmp_path) == []


def test_turned_hoop_turns_the_stitches(tmp_path):
    """A narrow piece forces the RE20b to be turned 90 degrees; the conductive half of the patch
    (x > 0 on the piece) must then be sewn at hoop y < its centre (hoop x = piece y, hoop
    y = -piece x)."""
    p = patch("t", 60, 60, 30, 0.8, "polygon:0,-20;20,-20;20,20;0,20")
    design = write_design(tmp_path / "design.json", [p], size=(400, 120), hoop="RE20b")
    out = tmp_path / "out"
    r = run("fabricate", design, "-o", out)
    assert r.exit_code == 0, r.output
    h = json.loads((out / "fabrication.json").read_text())["hoopings"][0]
    assert h["hoop"] == "RE20b" and h["orientation_deg"] == 90
    cx, cy = (10 * v for v in h["patches"][0]["position_hoop_mm"])
    d = jef.decode((out / "hoop01.jef").read_bytes())
    block, ys = 0, {0: [], 1: []}
    for c, _x, y in d.records:
        if c == dst.COLOR:
            block += 1
        elif c == dst.STITCH:
            ys[block].append(y - cy)
    # 0.1 mm; triangles are selected by centroid, so a 5 mm triangle may cross the line by 3 mm
    assert block == 1 and min(ys[1]) > -160 and max(ys[1]) < 35 and sum(ys[1]) / len(ys[1]) < -50
    assert max(ys[0]) > 100 and sum(ys[0]) / len(ys[0]) > 30


def test_ids_are_escaped_in_the_sheet_and_control_characters_refused(tmp_path):
    """An id that Markdown would interpret appears literally in fabrication.md (and unescaped
    in the HTML page and the JSON); an id holding NUL or a line break is refused."""
    from stitchswitch.layout.fabrication.sheet import md_escape

    assert md_escape("a|b*c_<d>") == "a\\|b\\*c\\_\\<d\\>"
    design = write_design(tmp_path / "design.json", [patch("p|*1*", 60, 60, 24, 0.8)])
    out = tmp_path / "out"
    assert run("fabricate", design, "-o", out).exit_code == 0
    md = (out / "fabrication.md").read_text()
    assert "p\\|\\*1\\*" in md and "p|*1*" not in md
    assert "p|*1*" in (out / "fabrication.html").read_text()
    for bad in ("p\x001", "p\n1"):
        design = write_design(tmp_path / "bad.json", [patch(bad, 60, 60, 24, 0.8)])
        r = run("fabricate", design, "-o", tmp_path / "none")
        assert r.exit_code == 2 and "$.patches[0].id" in r.output
        assert "control character" in r.output and not (tmp_path / "none").exists()


def test_templates_are_1_to_1_tiled_pdfs(tmp_path):
    """Each page is the paper's size and 1:1: the axes span the page minus 10 mm margins in
    data mm, so the 50 mm square prints as 50 mm."""
    import re

    design = write_design(tmp_path / "design.json", SMALL)
    out = tmp_path / "out"
    assert run("fabricate", design, "-o", out).exit_code == 0
    doc = json.loads((out / "fabrication.json").read_text())
    for h in doc["hoopings"]:
        for key, (w_pt, h_pt) in (("template_a4", (595.28, 841.89)),
                                  ("template_letter", (612.0, 792.0))):
            pdf = (out / h["files"][key]).read_bytes()
            assert pdf.startswith(b"%PDF")
            boxes = re.findall(rb"/MediaBox \[ *0 0 ([\d.]+) ([\d.]+) *\]", pdf)
            assert boxes and all(abs(float(a) - w_pt) < 0.5 and abs(float(b) - h_pt) < 0.5
                                 for a, b in boxes)
    again = tmp_path / "again"
    assert run("fabricate", design, "-o", again).exit_code == 0
    name = doc["hoopings"][0]["files"]["template_a4"]
    assert (out / name).read_bytes() == (again / name).read_bytes()

