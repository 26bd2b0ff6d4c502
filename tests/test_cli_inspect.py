"""``stitchswitch inspect``: counts, stitched extents about the hoop centre, fit by position,
the JEF header's hoop, and refused files."""
import json

import pytest
from click.testing import CliRunner

from stitchswitch.cli.main import cli

from helpers import EXTERNAL

STAR = EXTERNAL / "embroidery"


@pytest.mark.parametrize("name", ["Star.DST", "Star.JEF", "Star.EXP", "Star.pes"])
def test_inspect_star(name):
    r = CliRunner().invoke(cli, ["inspect", str(STAR / name)])
    assert r.exit_code == 0, r.output
    lines = dict(line.split(None, 1) for line in r.output.strip().splitlines()
                 if not line.startswith("header"))
    assert lines["extents"] == "59.1 x 62.3 mm of stitches"
    assert lines["fits"].startswith("SQ14b 140 x 140 mm")


def test_inspect_own_file_counts_trims(tmp_path):
    out = tmp_path / "p.jef"
    assert CliRunner().invoke(cli, ["patch", "-d", "40", "-p", "0.8", "-o", str(out)]).exit_code == 0
    r = CliRunner().invoke(cli, ["inspect", str(out)])
    assert r.exit_code == 0
    lines = dict(line.split(None, 1) for line in r.output.strip().splitlines())
    assert int(lines["trims"]) > 0 and lines["colours"].startswith("1")


def test_inspect_bad_file(tmp_path):
    bad = tmp_path / "x.txt"
    bad.write_text("hello")
    r = CliRunner().invoke(cli, ["inspect", str(bad)])
    assert r.exit_code == 2 and r.output.startswith("Error: ")
    r = CliRunner().invoke(cli, ["inspect", str(tmp_path / "missing.jef")])
    assert r.exit_code == 2 and "no such file" in r.output


@pytest.mark.parametrize("name, content, message", [
    ("e.DST", b"x", "1 bytes, too short for a DST file (at least 512)"),
    ("e.DST", b"", "0 bytes, too short for a DST file"),
    ("e.DST", b"LA:" + b" " * 509 + b"\x00\x00\xf3", "holds no stitches (not a DST design)"),
    ("e.pes", b"#PEC0001" + b"\x00" * 100, "not a PES file (it does not start with #PES)"),
    ("e.pes", b"#PES0001" + b"\xff" * 40, "not a readable PES file (malformed data)"),
    ("e.jef", b"\x00" * 200, "stitches lie at one point (not a JEF design)"),
    ("e.xyz", b"abc", "'xyz' is not an embroidery format pyembroidery reads"),
])
def test_empty_and_garbage_files_are_refused(tmp_path, name, content, message):
    """Empty or garbage files are one error naming the file, never a design of 0 stitches
    that fits every hoop, and never pyembroidery's own exception text."""
    bad = tmp_path / name
    bad.write_bytes(content)
    r = CliRunner().invoke(cli, ["inspect", str(bad)])
    assert r.exit_code == 2 and r.output.count("\n") == 1, r.output
    assert r.output.startswith(f"Error: {str(bad)!r}: ") and message in r.output


def _off_centre_jef(path):
    """A JEF written by pyembroidery itself: stitches from x = -3 to +95 mm and y = 40 to 70
    mm about the hoop centre, reached by a jump from the centre (the case of a hooping whose
    patches sit on one side of the hoop)."""
    import pyembroidery as pe
    p = pe.EmbPattern()
    p.add_thread({"color": 0x000000})
    p.add_stitch_absolute(pe.JUMP, 0, 0)
    for k in range(50):
        p.add_stitch_absolute(pe.STITCH, -30 + (980 * k) // 49, -400 - (300 if k % 2 else 0))
    p.add_stitch_absolute(pe.JUMP, 0, 0)
    p.end()
    pe.write(p, str(path))


def test_inspect_off_centre_fit_by_position(tmp_path):
    """Extents count the stitches, not the jump from the centre; the hoops that fit are those
    whose field holds the stitches where they lie, not the ones their size alone would fit."""
    out = tmp_path / "off.jef"
    _off_centre_jef(out)
    r = CliRunner().invoke(cli, ["inspect", str(out)])
    assert r.exit_code == 0, r.output
    lines = dict(line.split(None, 1) for line in r.output.strip().splitlines()
                 if not line.startswith("header"))
    assert lines["extents"] == "98.0 x 30.0 mm of stitches"
    assert lines["position"] == "x -3.0..+95.0 mm, y +40.0..+70.0 mm from the hoop centre"
    assert lines["fits"] == "SQ20b 200 x 200 mm, RE36b 200 x 360 mm"
    assert "SQ14b 140 x 140 mm" in lines["centred"]
    # pyembroidery's writer sizes the header hoop from the extents about the centre: 126 x 110
    assert ("header hoop  code 3, a 126 x 110 mm field (none of this machine's hoops); the "
            "stitches reach OUTSIDE this field") in r.output
    s = json.loads(CliRunner().invoke(cli, ["inspect", str(out), "--json"]).output)
    assert s["stitch_bounds_mm"] == [-3.0, 40.0, 95.0, 70.0]
    assert s["span_bounds_mm"] == [-3.0, 0.0, 95.0, 70.0]          # the jumps reach the centre
    assert s["header_hoop"] == {"code": 3, "field_mm": [126.0, 110.0], "catalogue_hoops": [],
                                "holds_stitches": False}


def test_inspect_names_the_header_hoop_of_our_jef(tmp_path):
    """Our JEF header carries the hoop it was made for (SQ14b: code 2, the 140 x 200 field);
    the code is read at the place the independent decoder reads it."""
    from decoders.jef import decode as decode_jef
    out = tmp_path / "p.jef"
    assert CliRunner().invoke(cli, ["patch", "-d", "40", "-p", "0.8", "-o", str(out)]).exit_code == 0
    r = CliRunner().invoke(cli, ["inspect", str(out)])
    assert decode_jef(out.read_bytes()).header["hoop"] == 2
    assert ("header hoop  code 2, a 140 x 200 mm field (SQ14b, RE20b); the stitches lie "
            "inside it") in r.output


def test_inspect_other_machine_and_bad_machine(tmp_path):
    machines = tmp_path / "m.json"
    machines.write_text(json.dumps({
        "format": "stitchswitch machines", "version": 1,
        "machines": [{"name": "tiny", "label": "Tiny", "stitches_per_minute": 400,
                      "default_format": "dst",
                      "hoops": [{"name": "T5", "width_mm": 50, "height_mm": 50, "margin_mm": 2,
                                 "frame_width_mm": 10, "jef_code": 1}]}]}))
    star = str(STAR / "Star.DST")
    r = CliRunner().invoke(cli, ["inspect", star, "--machines", str(machines), "--machine", "tiny"])
    assert r.exit_code == 0, r.output
    assert "fits      no hoop of the tiny (largest: T5 50 x 50 mm)" in r.output
    r = CliRunner().invoke(cli, ["inspect", star, "--machine", "nope"])
    assert r.exit_code == 2 and r.output.startswith("Error: ") and "'nope'" in r.output
