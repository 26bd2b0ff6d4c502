"""``stitchswitch preview``: design rendering, mesh export, single-patch view, errors."""
import json
import re

import meshio
import numpy as np
import pytest
from PIL import Image

from stitchswitch import Patch, solve

from helpers import cli_run as run


def design_file(tmp_path, edge_patch=False):
    patches = [{"id": "big", "piece": "front", "centre_mm": [50, 60], "diameter_mm": 60, "fill": 1.0},
               {"id": "small", "piece": "front", "centre_mm": [110, 60], "diameter_mm": 40,
                "fill": 0.8, "state": "down"}]
    if edge_patch:      # 3 mm from the piece outline: a piece-edge error in the check; a tall
        # dome (h 15.6 mm), lit brightly enough in the top view to tell its colour by thresholds
        patches.append({"id": "edge", "piece": "front", "centre_mm": [182, 60],
                        "diameter_mm": 50, "fill": 1.0})
    obj = {"version": 1,
           "pieces": [{"name": "front", "outline_mm": [[0, 0], [200, 0], [200, 120], [0, 120]]}],
           "patches": patches}
    path = tmp_path / "design.json"
    path.write_text(json.dumps(obj))
    return path


def test_design_preview_png_and_mesh(tmp_path):
    design = design_file(tmp_path)
    png, vtu = tmp_path / "p.png", tmp_path / "p.vtu"
    r = run("preview", design, "-o", png, "--view", "top", "--size", "320x240", "--mesh", vtu)
    assert r.exit_code == 0, r.output
    assert "patches  2 (1 up, 1 down)" in r.output
    img = np.asarray(Image.open(png))
    assert img.shape == (240, 320, 3) and len(np.unique(img.reshape(-1, 3), axis=0)) > 50
    mesh = meshio.read(vtu)
    assert f"({mesh.points.shape[0]} points)" in r.output
    index = mesh.point_data["patch_index"]
    assert mesh.points[index == 0, 2].max() == pytest.approx(solve(Patch(60.0, 1.0)).keypoints.h_mm,
                                                             abs=0.01)
    assert mesh.points[index == 1, 2].min() == pytest.approx(-solve(Patch(40.0, 0.8)).keypoints.h_mm,
                                                             abs=0.01)           # mixed: own state
    first = png.read_bytes()
    r = run("preview", design, "-o", png, "--view", "top", "--size", "320x240", "--state", "up")
    assert r.exit_code == 0 and "(2 up, 0 down)" in r.output
    assert png.read_bytes() != first
    r = run("preview", design, "-o", png, "--view", "top", "--size", "320x240")
    assert png.read_bytes() == first                                      # deterministic


def test_violations_colouring(tmp_path):
    design = design_file(tmp_path, edge_patch=True)
    png = tmp_path / "v.png"
    r = run("preview", design, "-o", png, "--view", "top", "--size", "320x240",
            "--color", "violations")
    assert r.exit_code == 0, r.output
    assert re.search(r"violations +2 errors", r.output)        # piece-edge and hoopable
    assert "error piece-edge" in r.output and "error hoopable" in r.output
    img = np.asarray(Image.open(png)).astype(int)
    red = (img[..., 0] > 180) & (img[..., 1] < 90) & (img[..., 2] < 90)
    green = (img[..., 1] > 130) & (img[..., 0] < 90) & (img[..., 2] < 90)
    assert red[:, 200:].sum() > 100 and red[:, :150].sum() < 20     # the edge patch, at the right
    assert green[:, :150].sum() > 100                                # the others are fine


def test_single_patch_view(tmp_path):
    out, ply = tmp_path / "patch.png", tmp_path / "patch.ply"
    r = run("preview", "--diameter", 40, "--fill", 0.8, "-o", out, "--mesh", ply)
    assert r.exit_code == 0, r.output
    kp = solve(Patch(40.0, 0.8)).keypoints
    assert f"h        {kp.h_mm:.3f} mm" in r.output
    assert out.read_bytes().startswith(b"\x89PNG")
    assert meshio.read(ply).points[:, 2].max() == pytest.approx(kp.h_mm, abs=0.01)
    svg = tmp_path / "patch.svg"
    r = run("preview", "-d", 40, "-p", 0.8, "-o", svg, "--state", "down")
    assert r.exit_code == 0, r.output
    assert f"h = {kp.h_mm:.2f} mm" in svg.read_text()


@pytest.mark.parametrize("args,message", [
    (["DESIGN", "--view", "front"], "'front' is not one of 'iso', 'top', 'side'"),
    (["DESIGN", "--size", "12"], "size: '12' must be WIDTHxHEIGHT"),
    (["DESIGN", "--size", "10x10"], "size: 10x10 is outside [64, 8192]"),
    (["DESIGN", "--mesh", "OUT/m.stl"], "unknown extension '.stl'; use .vtu, .ply, .obj"),
    (["DESIGN", "--color", "rainbow"], "'rainbow' is not one of 'height', 'violations'"),
    (["DESIGN", "-o", "OUT/p.jpg"], "the 3D preview of a design is written as .png"),
    (["DESIGN", "--diameter", "40"], "either a DESIGN file or --diameter/--fill, not both"),
    ([], "give a DESIGN file, or --diameter and --fill"),
    (["--diameter", "40"], "needs both --diameter and --fill"),
    (["-d", "40", "-p", "0.8", "--state", "mixed"], "--state mixed needs a design"),
    (["-d", "40", "-p", "0.8", "--view", "top"], "--view applies to the 3D preview"),
    (["-d", "40", "-p", "1.4"], "fill: 1.4 is outside (0, 1]"),
    (["OUT/missing.json"], "missing.json"),
    (["DESIGN", "--material", "m.json"], "--material is for the single-patch view"),
    (["DESIGN", "--patch", "nope"], "--patch: OUT/../design.json has no patch 'nope'; its patches: big, small"),
    (["DESIGN", "--piece", "back"], "has no piece 'back'; its pieces: front"),
    (["DESIGN", "--piece", "front", "--patch", "big"], "give --piece or --patch, not both"),
    (["DESIGN", "--view", "section"], "--view section needs --patch ID"),
    (["DESIGN", "--view", "section", "--patch", "big", "--color", "violations"],
     "--color violations applies to the 3D views"),
    (["DESIGN", "--exaggerate", "0.5"], "'--exaggerate': 0.5 is outside [1, 50]"),
    (["DESIGN", "--exaggerate", "nan"], "'--exaggerate'"),
    (["-d", "40", "-p", "0.8", "--patch", "big"], "--patch applies to the 3D preview"),
    (["-d", "40", "-p", "0.8", "--exaggerate", "2"], "--exaggerate applies to the 3D preview"),
])
def test_bad_input_is_one_line_and_writes_nothing(tmp_path, args, message):
    design = design_file(tmp_path)
    out = tmp_path / "out"
    out.mkdir()
    args = [str(design) if a == "DESIGN" else a.replace("OUT", str(out)) for a in args]
    message = message.replace("OUT/../design.json", str(design))
    if "-o" not in args:
        args += ["-o", str(out / "p.png")]
    r = run("preview", *args)
    assert r.exit_code == 2, r.output
    assert message in r.output and "Traceback" not in r.output
    assert len(r.output.strip().splitlines()) == 1
    assert list(out.iterdir()) == []


def test_framing_exaggeration_and_section_view(tmp_path):
    design = design_file(tmp_path)
    png = tmp_path / "p.png"
    r = run("preview", design, "-o", png, "--size", "320x240", "--patch", "big", "--exaggerate", "2")
    assert r.exit_code == 0, r.output
    assert "iso, 320x240 px, colour by height, framed on patch big, heights x 2" in r.output
    framed = png.read_bytes()
    assert run("preview", design, "-o", png, "--size", "320x240").exit_code == 0
    assert png.read_bytes() != framed
    r = run("preview", design, "-o", png, "--size", "500x300", "--view", "section", "--patch",
            "small", "--exaggerate", "3", "--mesh", tmp_path / "m.vtu")
    assert r.exit_code == 0, r.output
    assert "section through patch small, 500x300 px, heights x 3" in r.output
    img = np.asarray(Image.open(png))
    assert img.shape[:2] == (300, 500) and len(np.unique(img.reshape(-1, img.shape[2]), axis=0)) > 20
    mesh = meshio.read(tmp_path / "m.vtu")                 # the mesh keeps the true heights
    assert mesh.points[mesh.point_data["patch_index"] == 1, 2].min() == pytest.approx(
        -solve(Patch(40.0, 0.8)).keypoints.h_mm, abs=0.01)
