"""The placement marks as DXF: written by fabricate next to the PDF templates (garment mode),
read back with ezdxf, the same numbers as fabrication.json, byte-identical across runs."""
import json
import os

import ezdxf
import numpy as np

from stitchswitch.layout.fabrication.marks_dxf import LAYERS
from test_cli_fabricate import SMALL, write_design

from helpers import cli_run as run


def _fab(tmp_path, name="fab", *args):
    design = write_design(tmp_path / "design.json", SMALL)
    out = tmp_path / name
    r = run("fabricate", design, "-o", out, *args)
    assert r.exit_code == 0, r.output
    return out, json.loads((out / "fabrication.json").read_text())


def _by_layer(msp, layer, kind):
    return [e for e in msp if e.dxf.layer == layer and e.dxftype() == kind]


def test_marks_dxf_read_back(tmp_path):
    out, doc = _fab(tmp_path)
    eta = doc["stretch"]["eta"]
    outline = np.array([[0, 0], [300, 0], [300, 250], [0, 250]], dtype=float)
    for h in doc["hoopings"]:
        name = h["files"]["marks_dxf"]
        assert name == f"hoop{h['number']:02d}-marks.dxf"
        dxf = ezdxf.readfile(out / name)
        assert dxf.units == ezdxf.units.MM
        assert set(LAYERS) <= {layer.dxf.name for layer in dxf.layers}
        msp = dxf.modelspace()
        (piece,) = _by_layer(msp, "PIECE", "LWPOLYLINE")
        assert piece.closed and np.allclose(np.array(piece.get_points("xy")), outline)
        (field,) = _by_layer(msp, "HOOP_FIELD", "LWPOLYLINE")
        w, hh = (np.array(h["field_mm"]) / eta)[:: (-1 if h["orientation_deg"] == 90 else 1)]
        xy = np.array(field.get_points("xy"))
        assert np.allclose(xy.max(axis=0) - xy.min(axis=0), [w, hh])
        assert np.allclose(xy.mean(axis=0), h["centre_garment_mm"], atol=1e-3)
        points = [tuple(e.dxf.location)[:2] for e in _by_layer(msp, "MARKS", "POINT")]
        assert np.allclose(points, h["alignment_marks_garment_mm"], atol=1e-3)
        assert len(_by_layer(msp, "MARKS", "LINE")) == 2 * len(points)
        circles = _by_layer(msp, "PATCHES", "CIRCLE")
        assert len(circles) == len(h["patches"])
        for c, p in zip(circles, h["patches"]):
            assert np.allclose(tuple(c.dxf.center)[:2], p["centre_garment_mm"], atol=1e-3)
            assert abs(c.dxf.radius - p["diameter_mm"] / (2 * eta)) < 1e-6
        labels = {e.dxf.text for e in _by_layer(msp, "LABELS", "TEXT")}
        assert {p["id"] for p in h["patches"]} <= labels
    md = (out / "fabrication.md").read_text()
    assert "or cut/plot the marks from `hoop01-marks.dxf` (relaxed mm, 1:1)" in md


def test_marks_dxf_deterministic_and_garment_only(tmp_path):
    a, _ = _fab(tmp_path, "a")
    b, _ = _fab(tmp_path, "b")
    names = sorted(n for n in os.listdir(a) if n.endswith(".dxf"))
    assert names == ["hoop01-marks.dxf", "hoop02-marks.dxf"]
    for n in names:
        assert (a / n).read_bytes() == (b / n).read_bytes()
        assert b"$TDCREATE" in (a / n).read_bytes()      # the fixed date, not today's
    free, doc = _fab(tmp_path, "free", "--mode", "free")
    assert not [n for n in os.listdir(free) if n.endswith(".dxf")]
    assert all(h["files"]["marks_dxf"] is None for h in doc["hoopings"])
