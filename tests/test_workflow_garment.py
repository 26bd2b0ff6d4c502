"""The design workflow on a real Gerber AAMA pattern, from the command line only (no JSON
edited by hand): import a size, place three patches by target height, move one with edit,
check flags exactly what fabricate refuses, the fix clears it, fabricate succeeds with its
PDF templates, DXF marks and a sheet that says why each hoop; inspect reads the files back."""
import json

import ezdxf
import numpy as np

from helpers import EXTERNAL
from helpers import cli_run as run

TANK = EXTERNAL / "dxf" / "WM_LOOSE_SHAPE_TANK_AAMA.DXF"
PIECE = "RELAXED TANK FR V2"


def test_tank_workflow(tmp_path):
    design = tmp_path / "tank.json"
    r = run("import", TANK, "--size", "36", "--pieces", PIECE, "-o", design)
    assert r.exit_code == 0 and "x 7.8..686.2, y 503.9..794.3 mm" in r.output
    for at, h in (("150,650", 8), ("300,640", 12), ("450,580", 16)):
        r = run("place", design, "--piece", PIECE, "--at", at, "--height", h, "--id-prefix",
                "pocket")
        assert r.exit_code == 0, r.output
        assert "Warning" not in r.output
        line = [x for x in r.output.splitlines() if x.startswith("pocket")][-1]
        assert abs(float(line.split("h = ")[1].split(" mm")[0]) - h) <= 0.2
    assert run("check", design).exit_code == 0

    # move a patch 36 mm from the hem: on the piece, but no hoop frame fits on the cut piece
    r = run("edit", design, "pocket2", "--at", "150,540")
    assert r.exit_code == 0 and "Warning: hoopable" in r.output
    check = run("check", design, "--json")
    assert check.exit_code == 1
    found = json.loads(check.output)["violations"]
    assert [(v["rule"], v["patches"]) for v in found] == [("hoopable", ["pocket2"])]
    out = tmp_path / "fab"
    r = run("fabricate", design, "-o", out)
    assert r.exit_code == 2 and "patch 'pocket2' cannot be hooped" in r.output
    assert not out.exists()

    # the fix: hoop the piece as an uncut blank reaching 30 mm past the outline
    assert run("check", design, "--blank-margin", "30").exit_code == 0
    r = run("fabricate", design, "--blank-margin", "30", "-o", out)
    assert r.exit_code == 0, r.output
    doc = json.loads((out / "fabrication.json").read_text())
    assert sorted(p["id"] for h in doc["hoopings"] for p in h["patches"]) == \
        ["pocket1", "pocket2", "pocket3"]
    assert any("uncut blank reaching 30 mm" in s for s in doc["stretch"]["instructions"])
    for h in doc["hoopings"]:                       # the 1:1 printable templates
        for key in ("template_a4", "template_letter"):
            assert (out / h["files"][key]).read_bytes().startswith(b"%PDF")
        marks = ezdxf.readfile(out / h["files"]["marks_dxf"]).modelspace()  # and the DXF marks
        points = [tuple(e.dxf.location)[:2] for e in marks.query("POINT[layer=='MARKS']")]
        assert np.allclose(points, h["alignment_marks_garment_mm"], atol=1e-3)
        # inspect reads each machine file back: its stitches lie in the hooping's hoop
        r = run("inspect", out / h["files"]["embroidery"], "--json")
        assert r.exit_code == 0 and any(x.startswith(h["hoop"] + " ")
                                        for x in json.loads(r.output)["hoops"])
    sheet = (out / "fabrication.md").read_text()
    assert sheet.count("why this hoop: ") == len(doc["hoopings"])
    assert "| frame on a stitched patch | never |" in sheet
    assert run("layout", design, "-o", tmp_path / "layout.pdf").exit_code == 0
