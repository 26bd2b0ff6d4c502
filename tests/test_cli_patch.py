import re

import pytest
from click.testing import CliRunner

from stitchswitch.cli.main import cli

from decoders import dst, jef


def run(*args):
    return CliRunner().invoke(cli, list(args))


def test_patch_writes_jef_and_preview(tmp_path):
    out, png = tmp_path / "patch.jef", tmp_path / "plan.png"
    r = run("patch", "--diameter", "40", "--fill", "0.8", "--conductive", "ring:0,1",
            "-o", str(out), "--preview", str(png))
    assert r.exit_code == 0, r.output
    assert "fill           0.8000" in r.output
    n = int(re.search(r"stitches +(\d+)", r.output).group(1))
    crossings = re.search(r"gap crossings +(\d+) \(([\d.]+) mm", r.output)
    assert crossings and "electrodes     1 thread(s)" in r.output
    d = jef.decode(out.read_bytes())
    assert d.count(dst.STITCH) == n and d.count(dst.COLOR) == 1
    assert d.header["hoop"] == 2                       # SQ14b -> code 2 (docs/embroidery.md)
    assert png.read_bytes().startswith(b"\x89PNG")
    first = out.read_bytes()
    assert run("patch", "-d", "40", "-p", "0.8", "--conductive", "ring:0,1",
               "-o", str(out)).exit_code == 0
    assert out.read_bytes() == first


def test_patch_format_option(tmp_path):
    out = tmp_path / "p.bin"
    r = run("patch", "-d", "30", "-p", "0.6", "--resolution", "4", "--format", "dst", "-o", str(out))
    assert r.exit_code == 0, r.output
    assert dst.decode(out.read_bytes()).records[-1][0] == dst.END


@pytest.mark.parametrize("args,message", [
    (["--format", "xyz"], "unsupported embroidery format 'xyz'; supported: dst, exp, jef, pes, vp3"),
    (["--diameter", "250"], "fits no hoop; the largest is RE36b 200 x 360 mm"),
    (["--fill", "1.5"], "fill 1.5 is outside (0, 1]"),
    (["--conductive", "blob:1"], "unknown selection 'blob:1'"),
])
def test_patch_errors(tmp_path, args, message):
    out = tmp_path / "p.jef"
    base = {"--diameter": "40", "--fill": "0.8"}
    for k, v in zip(args[::2], args[1::2]):
        base[k] = v
    flat = [x for kv in base.items() for x in kv if kv[0] != "--format"]
    if "--format" in base:
        flat += ["--format", base["--format"]]
    r = run("patch", *flat, "-o", str(out))
    assert r.exit_code == 2
    assert message in r.output and r.output.startswith("Error: ")
    assert len(r.output.strip().splitlines()) == 1
    assert not out.exists()


STAR = "29,0;10,7;9,28;-8,11;-23,17;-12,0;-23,-17;-8,-11;9,-28;10,-7"


def test_composite_patch_with_outline(tmp_path):
    out = tmp_path / "c.jef"
    r = run("patch", "-d", "60", "-p", "0.5", "--core", "20,1.0", "--outline", STAR,
            "--conductive", "ring:0", "-o", str(out))
    assert r.exit_code == 0, r.output
    assert "surround 0.5, core 1.0" in r.output
    d = jef.decode(out.read_bytes())
    assert d.count(dst.COLOR) == 1 and d.count(dst.STITCH) > 1000
    xs = [rec[1] for rec in d.records if rec[0] == dst.STITCH]
    ys = [rec[2] for rec in d.records if rec[0] == dst.STITCH]
    # 0.1 mm units: inside the star (x -23..29, y -28..28 mm) and spanning most of it
    assert 400 <= max(xs) - min(xs) <= 522 and 450 <= max(ys) - min(ys) <= 560


@pytest.mark.parametrize("args,message", [
    (["--outline", STAR], "a custom outline needs a composite core"),
    (["--core", "20,1.0", "--outline", "40,0;0,20;-20,-20"], "beyond the bounding circle"),
    (["--core", "70,1.0"], "core diameter 70 mm must be > 0 and below the diameter 60 mm"),
    (["--core", "20"], "--core: '20' is not D,P"),
    (["--core", "20,1.0", "--outline", "29,0;0,1;-29,0;0,-1"], "core disc (20 mm) is not inside the outline"),
])
def test_composite_errors(tmp_path, args, message):
    out = tmp_path / "c.jef"
    r = run("patch", "-d", "60", "-p", "0.5", *args, "-o", str(out))
    assert r.exit_code == 2, r.output
    assert message in r.output and len(r.output.strip().splitlines()) == 1
    assert not out.exists()


def test_patch_refuses_an_empty_conductive_selection_and_a_hoop_without_margin(tmp_path):
    out = tmp_path / "p.jef"
    r = run("patch", "-d", "40", "-p", "0.6", "--conductive", "ring:99", "-o", str(out))
    assert r.exit_code == 2 and "Error: --conductive 'ring:99' selects no triangle" in r.output
    r = run("patch", "-d", "138", "-p", "0.6", "--hoop", "SQ14b", "-o", str(out))
    assert r.exit_code == 2 and "within its 5 mm margin" in r.output
    assert not out.exists()


def test_patch_warns_of_narrow_gaps_and_experimental_formats(tmp_path):
    r = run("patch", "-d", "40", "-p", "0.6", "--resolution", "2", "-o", str(tmp_path / "p.vp3"))
    assert r.exit_code == 0, r.output
    assert "gaps of 0.26 mm between triangles are narrower than 0.3 mm" in r.output
    assert "VP3 is experimental" in r.output
    trim = run("patch", "-d", "40", "-p", "0.6", "--travel", "trim", "-o", str(tmp_path / "t.jef"))
    assert re.search(r"gap crossings +0 ", trim.output), trim.output


def test_help_marks_exp_and_vp3_experimental():
    r = run("patch", "--help")
    assert r.exit_code == 0
    assert "EXP, VP3 experimental" in " ".join(r.output.split())
