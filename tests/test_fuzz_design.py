"""Fuzzing the design file loader: structured edits and byte edits of a small valid design
(two pieces, a plain and a composite patch) load or give one short error naming the file."""
import json

from hypothesis import given

from stitchswitch.layout.garment.design_io import load_design

from fuzz_edits import byte_edit, json_edit
from fuzzing import FUZZ, check_refusal, edited

DESIGN = {
    "version": 1,
    "pieces": [{"name": "front", "size": "M", "source": "test",
                "outline_mm": [[0, 0], [300, 0], [300, 250], [0, 250]]},
               {"name": "back", "outline_mm": [[0, 0], [200, 0], [100, 150]]}],
    "patches": [
        {"id": "a", "piece": "front", "centre_mm": [60, 60], "diameter_mm": 24, "fill": 0.8,
         "conductive": "ring:0", "threads": {"top": "#1b1b1b", "conductive": "#b0b0b0"},
         "state": "up"},
        {"id": "b", "piece": "front", "centre_mm": [150, 120], "diameter_mm": 40, "fill": 0.7,
         "composite": {"core_diameter_mm": 20, "core_fill": 0.9},
         "outline_mm": [[-20, 0], [0, -20], [20, 0], [0, 20]]}],
    "material": {"name": "default"},
    "machine": {"name": "janome-550e", "hoop": "SQ14b"},
}


def test_the_seed_loads(tmp_path):
    path = tmp_path / "design.json"
    path.write_text(json.dumps(DESIGN))
    assert len(load_design(path).patches) == 2


@FUZZ
@given(data=edited(json.dumps(DESIGN, indent=1).encode(), byte_edit, json_edit, json_edit))
def test_corrupted_copies(tmp_path, data):
    check_refusal(load_design, tmp_path / "design.json", data=data)
