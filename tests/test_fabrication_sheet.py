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


def _sheet_name(thread: dict) -> str:
    """The thread's name on the sheet, as docs/fabrication.md gives it, from fabrication.json."""
    j = thread.get("jef_thread")
    if j is None:
        return thread["colour"]
    return (f"{j['name']}, Janome {j['number']} (JEF colour {j['index']}, design colour "
            f"{thread['colour']})")


def test_colour_stops_say_what_to_do(tmp_path):
    """Patch a has a conductive ring: its hooping's file has one colour change, and the sheet
    says to change the bobbin there, and to put the normal one back after the file."""
    out, doc = _fabricate(tmp_path, SMALL)
    md = (out / "fabrication.md").read_text()
    h = next(h for h in doc["hoopings"] if any(p["id"] == "a" for p in h["patches"]))
    assert h["colour_changes"] == 1
    part = md.split(f"### Hooping {h['number']}")[1].split("### Hooping")[0]
    steps = [line for line in part.splitlines() if line[:1].isdigit()]
    names = [_sheet_name(t) for t in h["threads"]]
    top = [t for t in h["threads"] if t["role"] == "top"][0]
    assert any(s.endswith(f"Thread {names[0]} on top, a normal bobbin in; the machine "
                          f"sews {', '.join(top['patches'])}.") for s in steps)
    stop = [s for s in steps if "Colour stop 1:" in s]
    assert len(stop) == 1 and "put the conductive bobbin in" in stop[0]
    assert f"top thread {names[1]}; the machine then sews a (conductive thread)" in stop[0]
    if h["files"]["embroidery"].endswith(".jef"):          # the name the 550E shows
        assert "Pale Sky, Janome 216" in stop[0]
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
    pairs = [patch("a", 50, 50, 40, 0.8), patch("b", 50 + 150 / 1.7, 50, 40, 0.8),   # across
             patch("c", 250, 50, 40, 0.8), patch("d", 250, 50 + 150 / 1.7, 40, 0.8)]  # along y
    out, doc = _fabricate(tmp_path, pairs, "--hoop", "RE20b")
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


#: four patches so close that with the fewest hoopings (2 in the SQ14b) one frame lands on a
#: stitched patch; three hoopings avoid it (found by the conflict search, see
#: tests/test_conflict_plan.py)
CLOSE = [patch("a", 216.0, 114.5, 26.5, 0.8), patch("b", 136.5, 97.0, 28.8, 0.8),
         patch("c", 113.3, 155.3, 23.7, 0.8), patch("d", 171.9, 163.3, 32.1, 0.8)]


def test_sheet_says_why_a_hooping_more(tmp_path):
    design = write_design(tmp_path / "design.json", CLOSE, size=(306, 259))
    out = tmp_path / "fab"
    r = run("fabricate", design, "--hoop", "SQ14b", "-o", out)
    assert r.exit_code == 0, r.output
    assert "conflicts   none; 2 hooping(s) would leave 1" in r.output
    doc = json.loads((out / "fabrication.json").read_text())
    g = doc["grouping"]
    assert len(doc["hoopings"]) == 3 and doc["order"]["conflicts"] == []
    assert (g["fewest_hoopings"], g["fewest_hoopings_conflicts"], g["conflicts_exact"]) == \
        (2, 1, True)
    md = (out / "fabrication.md").read_text()
    assert ("| hoopings | 3, in the order below: 1 more than the fewest possible (2), because "
            "with 2 a hoop frame would land on a stitched patch 1 time(s), which can crush it |"
            ) in md
    r = run("fabricate", design, "--hoop", "SQ14b", "-o", tmp_path / "again")
    assert (tmp_path / "again" / "fabrication.md").read_bytes() == md.encode()


def test_unavoidable_conflict_named_with_what_to_do(tmp_path):
    """Two 70 mm patches 95 mm apart on the stretched fabric: no SQ14b field holds both and
    every field holding one puts its frame on the other, so one conflict is unavoidable; the
    sheet names the frame, the patch and what to do, in the conflict list and in the steps."""
    design = write_design(tmp_path / "design.json", [patch("a", 100, 100, 70, 0.8),
                                                     patch("b", 100 + 95 / 1.7, 100, 70, 0.8)])
    out = tmp_path / "fab"
    r = run("fabricate", design, "--hoop", "SQ14b", "-o", out)
    assert r.exit_code == 0, r.output
    assert "conflicts   1, the fewest possible (see fabrication.md)" in r.output
    doc = json.loads((out / "fabrication.json").read_text())
    (c,) = doc["order"]["conflicts"]
    assert c["hooping"] == 2 and c["stitched_in_hooping"] == 1
    md = (out / "fabrication.md").read_text()
    assert ("1 place(s) where a frame lands on a patch stitched earlier; this is the fewest "
            "possible over the hoop positions tried") in md
    assert (f"- hooping 2: its frame lands on patch {c['patch']}, stitched in hooping 1. Before "
            "clamping, lay a folded cloth or foam strip over") in md
    second = md.split("### Hooping 2")[1]
    assert f"Pad before clamping: the frame lands on {c['patch']} (stitched in hooping 1)." \
        in second


def test_small_pieces_are_warned_on_the_sheet(tmp_path):
    """Patch b (d 20, p 0.7) tessellates with pieces under 1 mm^2: its hooping counts them and
    the sheet warns; a d 40 patch has none and gets no warning."""
    from stitchswitch.layout.embroidery.patch_geometry import make_patch
    from stitchswitch.layout.embroidery.stitches import SMALL_PIECE_AREA_MM2

    expected = int((make_patch(20, 0.7, 5.0).areas_mm2 < SMALL_PIECE_AREA_MM2).sum())
    assert expected > 0
    (tmp_path / "one").mkdir()
    (tmp_path / "two").mkdir()
    out, doc = _fabricate(tmp_path / "one", [patch("b", 110, 70, 20, 0.7)])
    (h,) = doc["hoopings"]
    assert h["small_pieces"] == expected
    assert f"warning: {expected} stitched piece(s) under 1 mm^2" in (out / "fabrication.md").read_text()
    out, doc = _fabricate(tmp_path / "two", [patch("e", 110, 70, 40, 0.8)])
    assert [h["small_pieces"] for h in doc["hoopings"]] == [0]
    assert "stitched piece(s) under" not in (out / "fabrication.md").read_text()
