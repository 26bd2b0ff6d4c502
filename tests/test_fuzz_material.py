"""Fuzzing the material JSON loader (``--material``, a design's ``material.file``): structured
edits and byte edits of the shipped default material load or give one short error naming the
file."""
import json
from importlib import resources

from hypothesis import given

from stitchswitch.reduced.model.material_io import load_material

from fuzzing import FUZZ, byte_edits, check_refusal, json_edits

SEED = resources.files("stitchswitch").joinpath("data/default_material.json").read_bytes()


@FUZZ
@given(text=json_edits(json.loads(SEED)))
def test_json_edits(tmp_path, text):
    path = tmp_path / "material.json"
    path.write_text(text, encoding="utf-8")
    check_refusal(load_material, path)


@FUZZ
@given(data=byte_edits(SEED))
def test_byte_edits(tmp_path, data):
    path = tmp_path / "material.json"
    path.write_bytes(data)
    check_refusal(load_material, path)
