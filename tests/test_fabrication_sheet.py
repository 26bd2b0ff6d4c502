"""The fabrication sheet as a workshop uses it: plain language first, a legend of every mark,
per hooping the steps in order with the colour stops and why its hoop, the algorithm's figures
only at the end, and the same content in Markdown, HTML and fabrication.json."""
import json

from test_cli_fabricate import SMALL, patch, write_design

from helpers import cli_run as run


def _fabricate(tmp_path, patches, *args):
    design = write_design(tmp_path / "design.json", patches)
    out = tmp_path / "fab"
    r = run("fabricate", design, "-o", out, *args)
    assert r.exit_code == 0, r.output
    return out, json.loads((out / "fabrication.json").read_text())


def test_sheet_reads_in_workshop_order(tmp_path):
    out, doc = _fabricate(tmp_path, SMALL)
    md = (out / "fabrication.md").read_text()
    sections = [line for line in md.splitlines() if line.startswith("## ")]
    assert sections == ["## Before you start", "## What the drawings show",
                        "## Hoopings in stitching order", "## Frame conflicts",
                        "## How the hoopings were found", "## Limits"]
    head = md.split("## How the hoopings were found")[0]
    for jargon in ("first-fit", "mip", "gap 0.00", "HiGHS", "candidates"):  # none before the end
        assert jargon not in head, jargon
    assert "| frame on a stitched patch | never |" in md
    for mark in ("grey band", "red cross", "dotted circle", "50 mm square (templates)"):
        assert f"| {mark} |" in md
    html = (out / "fabrication.html").read_text()
    for title in ("What the drawings show", "How the hoopings were found"):
        assert title in html
    for h in doc["hoopings"]:
        assert h["hoop_reason"] and f"why this hoop: {h['hoop_reason']}" in md
        assert f"Load `{h['files']['embroidery']}` on the machine." in md
        assert f"Load {h['files']['embroidery']} on the machine." in html


def test_colour_stops_say_what_to_do(tmp_path):
    """Patch a has a conductive ring: its hooping's file has one colour change, and the sheet
    says to change the bobbin there, and to put the normal one back after the file."""
    out, doc = _fabricate(tmp_path, SMALL)
    md = (out / "fabrication.md").read_text()
    h = next(h for h in doc["hoopings"] if any(p["id"] == "a" for p in h["patches"]))
    assert h["colour_changes"] == 1
    part = md.split(f"### Hooping {h['number']}")[1].split("### Hooping")[0]
    steps = [line for line in part.splitlines() if line[:1].isdigit()]
    top = [t for t in h["threads"] if t["role"] == "top"][0]
    assert any(s.endswith(f"Thread {top['colour']} on top, a normal bobbin in; the machine "
                          f"sews {', '.join(top['patches'])}.") for s in steps)
    stop = [s for s in steps if "Colour stop 1:" in s]
    assert len(stop) == 1 and "put the conductive bobbin in" in stop[0]
    assert "the machine then sews a in #b0b0b0 (conductive thread)" in stop[0]
    assert not any("Colour stop 2" in s for s in steps)
    assert "When the file ends: put the normal bobbin back" in part


def test_hoop_reasons(tmp_path):
    """A patch alone gets the smallest hoop that holds it and the sheet says so; two patches
    too far apart for the SQ14b get the long hoop with their span stated."""
    out, doc = _fabricate(tmp_path, [patch("a", 100, 100, 40, 0.8)])
    (h,) = doc["hoopings"]
    assert h["hoop"] == "SQ14b"
    assert h["hoop_reason"].startswith("SQ14b is the smallest hoop whose field, less its 5 mm "
                                       "margin (130 x 130 mm), holds them: patch a spans 40 x "
                                       "40 mm")
    (tmp_path / "b").mkdir()
    out, doc = _fabricate(tmp_path / "b", [patch("a", 100, 60, 40, 0.8),
                                           patch("b", 100, 160, 40, 0.8)], "--hoop", "RE36b")
    (h,) = doc["hoopings"]                  # only the RE36b may be used: no smaller one tried
    assert h["hoop_reason"].startswith("RE36b is the smallest hoop whose field, less its 5 mm "
                                       "margin (190 x 350 mm), holds them: these 2 patches "
                                       "span 40 x 210 mm")


def test_which_way_up(tmp_path):
    """A turned hooping says where the pattern's up points; a straight one too."""
    out, doc = _fabricate(tmp_path, SMALL + [patch("d", 150, 40, 60, 0.8)], "--hoop", "RE20b")
    md = (out / "fabrication.md").read_text()
    turns = {h["orientation_deg"] for h in doc["hoopings"]}
    assert turns == {0, 90}, turns                 # both texts are exercised
    for h in doc["hoopings"]:
        text = ("turned a quarter: the hoop lies across the piece, the pattern's up (+y) pointing "
                "to your right and its +x towards you" if h["orientation_deg"] == 90 else
                "straight: the pattern's up (+y) pointing away from you and its +x to your right")
        assert f"Hoop it in the RE20b, {text}" in md
        # the marks agree: the hoop's right-hand mark (its +x side) lies along the pattern's
        # +y when turned, along its +x when straight; the top mark (away from you) along -x / +y
        (cx, cy), right, top = h["alignment_marks_garment_mm"][:3]
        if h["orientation_deg"] == 90:
            assert right[1] > cy and abs(right[0] - cx) < 1e-6 and top[0] < cx
        else:
            assert right[0] > cx and abs(right[1] - cy) < 1e-6 and top[1] > cy
