"""The JEF thread palette: the thread each colour block gets in the file is the one the
fabrication sheet and ``stitchswitch patch`` name (decoded from the written JEF's colour table),
and the header label comes from the design's name."""
import json
import re

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as hs

from stitchswitch.layout.embroidery import export
from stitchswitch.layout.embroidery import stitches as st
from stitchswitch.layout.embroidery.jef_palette import jef_threads, palette
from stitchswitch.layout.fabrication.document import Thread

from decoders import dst, jef
from helpers import cli_run as run


def blocks_plan(rgbs):
    """A plan of one short run per thread, a colour change between runs."""
    xy, cmd = [], []
    for k in range(len(rgbs)):
        if k:
            xy.append(xy[-1])
            cmd.append(st.COLOR_CHANGE)
        for i in range(4):
            xy.append((k * 3.0 + i, float(i % 2)))
            cmd.append(st.STITCH)
    xy.append(xy[-1])
    cmd.append(st.END)
    threads = tuple(st.Thread(f"t{k}", tuple(c)) for k, c in enumerate(rgbs))
    return st.StitchPlan(np.asarray(xy, dtype=float), np.asarray(cmd, dtype=np.int8), threads, 800.0)


def test_palette_is_the_janome_table():
    entries = palette()
    assert len(entries) == 78 and [t.index for t in entries] == list(range(1, 79))
    assert (entries[0].name, entries[0].number, entries[0].colour) == ("Black", "002", "#000000")
    assert (entries[9].name, entries[9].number) == ("Red", "225")
    assert len({t.number for t in entries}) == 78          # one Janome number per entry


def test_exact_palette_colours_get_their_own_entry():
    reds = jef_threads(["#ff0000", "#0b2f84", "#ff0000"])
    assert [t.index for t in reds] == [10, 12, 10]


def test_consecutive_blocks_landing_on_one_entry_take_the_next_nearest():
    a, b = jef_threads(["#000000", "#010101"])
    assert a.index == 1 and b.index != 1
    assert [t.index for t in jef_threads(["#000000", "#000000"])] == [1, 58]  # top, conductive


colour = hs.tuples(*[hs.integers(0, 255)] * 3)


@settings(max_examples=60, deadline=None)
@given(hs.lists(colour, min_size=1, max_size=5))
def test_the_written_jef_stores_the_threads_we_name(rgbs):
    data = export.encode(blocks_plan(rgbs), "jef")
    decoded = jef.decode(data)
    assert decoded.header["palette"] == [t.index for t in jef_threads(rgbs)]
    assert decoded.count(dst.COLOR) == len(rgbs) - 1


def test_sheet_names_jef_threads_only_for_jef_files():
    jefs = jef_threads(["#1b1b1b", "#b0b0b0"])
    names = [Thread("top", c, ("a",), j).sheet_name() for c, j in zip(["#1b1b1b", "#b0b0b0"], jefs)]
    assert names[0].startswith("Dark Sepia, Janome 260 (JEF colour 58")
    assert "design colour #b0b0b0" in names[1]
    assert Thread("top", "#1b1b1b", ("a",)).sheet_name() == "#1b1b1b"


def _design(path):
    patches = [{"id": "a", "piece": "front", "centre_mm": [60, 60], "diameter_mm": 24,
                "fill": 0.8, "conductive": "ring:0",
                "threads": {"top": "#1b1b1b", "conductive": "#b0b0b0"}},
               {"id": "c", "piece": "front", "centre_mm": [110, 60], "diameter_mm": 24,
                "fill": 0.9, "threads": {"top": "#204080", "conductive": "#b0b0b0"}}]
    obj = {"version": 1, "pieces": [{"name": "front", "outline_mm": [[0, 0], [200, 0],
                                                                    [200, 150], [0, 150]]}],
           "patches": patches}
    path.write_text(json.dumps(obj))
    return path


def test_fabrication_sheet_and_jef_name_the_same_threads(tmp_path):
    out = tmp_path / "out"
    r = run("fabricate", _design(tmp_path / "sleeve.json"), "-o", out)
    assert r.exit_code == 0, r.output
    doc = json.loads((out / "fabrication.json").read_text())
    sheet = (out / "fabrication.md").read_text()
    assert doc["schema"] == 2
    for h in doc["hoopings"]:
        decoded = jef.decode((out / h["files"]["embroidery"]).read_bytes())
        shown = jef_threads([t["colour"] for t in h["threads"]])
        assert decoded.header["palette"] == [t.index for t in shown]
        # fabrication.json records the palette thread the file stores for each block
        assert [t["jef_thread"] for t in h["threads"]] == [
            {"index": i, "number": t.number, "name": t.name, "colour": t.colour}
            for i, t in zip(decoded.header["palette"], shown)]
        for t, thread in zip(shown, h["threads"]):
            assert (f"{thread['role']} {t.name}, Janome {t.number} (JEF colour {t.index}, "
                    f"design colour {thread['colour']})") in sheet
    assert "Dark Sepia, Janome 260" in sheet and "Pale Sky, Janome 216" in sheet
    assert "put the conductive bobbin in" in sheet and "normal bobbin back" in sheet


def test_fabricated_dst_is_labelled_with_the_design_name(tmp_path):
    out = tmp_path / "out"
    r = run("fabricate", _design(tmp_path / "sleeve.json"), "--format", "dst", "-o", out)
    assert r.exit_code == 0, r.output
    assert dst.decode((out / "hoop01.dst").read_bytes()).header["LA"] == "sleeve hoop01"
    assert "JEF colour" not in (out / "fabrication.md").read_text()   # a DST has no palette
    doc = json.loads((out / "fabrication.json").read_text())
    assert doc["schema"] == 2
    assert all("jef_thread" not in t for h in doc["hoopings"] for t in h["threads"])


def test_patch_prints_the_machine_threads_and_labels_the_file(tmp_path):
    out = tmp_path / "Sleeve-button.jef"
    r = run("patch", "-d", "30", "-p", "0.8", "--conductive", "ring:0", "-o", out)
    assert r.exit_code == 0, r.output
    decoded = jef.decode(out.read_bytes())
    shown = jef_threads([st.NORMAL_THREAD.rgb, st.CONDUCTIVE_THREAD.rgb])
    assert decoded.header["palette"] == [t.index for t in shown]
    assert re.search(rf"thread 1 +embroidery thread: {shown[0].name} \(Janome {shown[0].number}",
                     r.output), r.output
    assert f"thread 2       conductive thread: {shown[1].name} (Janome {shown[1].number}" in r.output
    dst_out = tmp_path / "Sleeve-button.dst"
    assert run("patch", "-d", "30", "-p", "0.8", "-o", dst_out).exit_code == 0
    assert dst.decode(dst_out.read_bytes()).header["LA"] == "Sleeve-button"
