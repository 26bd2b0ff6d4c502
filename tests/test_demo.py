"""The built-in demos end to end: every step's output exists and is what it says,
the JEF decodes, and a rerun gives identical files."""
import json

import pytest
from click.testing import CliRunner

from stitchswitch import Patch
from stitchswitch.cli.main import cli
from stitchswitch.demos.tennis_pocket import BALL_DIAMETER_MM, POCKET_HEIGHT_MM

from decoders import dst, jef

EXPECTED = {"design.json", "check.json", "preview.png", "preview.vtu", "patch.png",
            "summary.html", "fabrication/fabrication.html", "fabrication/fabrication.json"}


def run(*args):
    return CliRunner().invoke(cli, list(args))


@pytest.fixture(scope="module")
def pocket(tmp_path_factory):
    out = tmp_path_factory.mktemp("demo") / "pocket"
    r = run("demo", "-o", str(out))             # the default demo: tennis-pocket
    assert r.exit_code == 0, r.output
    return out, r.output


def test_pocket_outputs(pocket):
    out, text = pocket
    files = {str(p.relative_to(out)) for p in out.rglob("*") if p.is_file()}
    assert EXPECTED <= files
    for k in range(1, 6):
        assert f"[{k}/5]" in text
    assert "summary.html" in text and "finished in" in text
    design = json.loads((out / "design.json").read_text())
    (patch,) = design["patches"]
    assert patch["piece"] == "skirt-front"
    fab = json.loads((out / "fabrication/fabrication.json").read_text())
    assert fab["grouping"]["hoopings"] == 1
    jefs = sorted(out.glob("fabrication/*.jef"))
    assert len(jefs) == 1
    decoded = jef.decode(jefs[0].read_bytes())
    assert decoded.count(dst.STITCH) == fab["hoopings"][0]["stitches"]
    page = (out / "summary.html").read_text()
    for section in ("1. Inverse design", "2. Placement", "3. Constraint check", "4. Preview",
                    "5. Fabrication", "data:image/png;base64,"):
        assert section in page
    assert (out / "preview.png").read_bytes().startswith(b"\x89PNG")


def test_pocket_check_json_is_the_check_commands(pocket):
    """check.json carries the same violations and small-pieces warnings as ``check --json``."""
    out, _ = pocket
    saved = json.loads((out / "check.json").read_text())
    r = run("check", str(out / "design.json"), "--json")
    assert r.exit_code in (0, 1), r.output
    live = json.loads(r.output)
    assert saved["clean"] == live["clean"]
    assert saved["small_pieces"] == live["small_pieces"]
    assert [v["rule"] for v in saved["violations"]] == [v["rule"] for v in live["violations"]]


def test_pocket_meets_its_target(pocket):
    from stitchswitch import Patch, solve

    out, _ = pocket
    (patch,) = json.loads((out / "design.json").read_text())["patches"]
    kp = solve(Patch(patch["diameter_mm"], patch["fill"])).keypoints
    assert kp.h_mm == pytest.approx(POCKET_HEIGHT_MM, abs=0.2)        # the pocket's depth
    assert kp.r_a_mm == pytest.approx(BALL_DIAMETER_MM / 2, abs=2.0)   # holds the ball


def test_rerun_gives_identical_files(pocket, tmp_path):
    out, _ = pocket
    again = tmp_path / "again"
    assert run("demo", "tennis-pocket", "-o", str(again)).exit_code == 0
    for name in EXPECTED | {"fabrication/hoop01.jef"}:
        assert (out / name).read_bytes() == (again / name).read_bytes(), name


def test_forearm_interface(tmp_path):
    out = tmp_path / "arm"
    r = run("demo", "forearm-interface", "-o", str(out))
    assert r.exit_code == 0, r.output
    design = json.loads((out / "design.json").read_text())
    patches = design["patches"]
    assert len(patches) == 6 and all(p["conductive"] == "ring:0" for p in patches)
    tiers = {p["id"].rstrip("0123456789") for p in patches}
    assert tiers == {"soft", "medium", "firm"}
    page = (out / "summary.html").read_text()
    assert "force in [0.1, 0.2] N" in page and "force in [0.4, 0.5] N" in page
    fab = json.loads((out / "fabrication/fabrication.json").read_text())
    for h in fab["hoopings"]:
        assert h["colour_changes"] >= 1          # the conductive centres are a second thread
    # the soft tier springs back, the medium and firm tiers are bistable (the shell's verdict),
    # in the console and the summary
    for text in (r.output, page):
        assert "soft buttons (d" in text and "the shell finds spring-back" in text
        assert text.count("the shell finds bistable") == 2 and "wanted" not in text
    from stitchswitch.fem_reference.snap import bistability
    from stitchswitch.fem_reference.snap.regions import cell_verdict

    firm = next(p for p in patches if p["id"].startswith("firm"))
    assert cell_verdict(bistability(Patch(firm["diameter_mm"], firm["fill"]))) == "bistable"


def test_unknown_demo_and_busy_outdir(tmp_path):
    r = run("demo", "nope", "-o", str(tmp_path / "x"))
    assert r.exit_code == 2 and "unknown demo 'nope'" in r.output
    assert not (tmp_path / "x").exists()
    busy = tmp_path / "busy"
    busy.mkdir()
    (busy / "keep.txt").write_text("mine")
    r = run("demo", "-o", str(busy))
    assert r.exit_code == 2 and "is not empty" in r.output
    assert r.output.startswith("Error:")                  # refused before any work
    assert [p.name for p in busy.iterdir()] == ["keep.txt"]
