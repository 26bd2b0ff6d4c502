"""Fuzzing the material JSON loader (``--material``, a design's ``material.file``): structured
edits and byte edits of the shipped default material load or give one short error naming the
file."""
from importlib import resources

from hypothesis import given

from stitchswitch.reduced.model.material_io import load_material

from fuzz_edits import byte_edit, json_edit
from fuzzing import FUZZ, check_refusal, edited

SEED = resources.files("stitchswitch").joinpath("data/default_material.json").read_bytes()


@FUZZ
@given(data=edited(SEED, byte_edit, json_edit, json_edit))
def test_corrupted_copies(tmp_path, data):
    check_refusal(load_material, tmp_path / "material.json", data=data)
