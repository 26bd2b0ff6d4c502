"""Fuzzing the machine catalogue loader (``--machines``): structured edits and byte edits of the
shipped catalogue load or give one short error naming the file."""
import json
from importlib import resources

from hypothesis import given

from stitchswitch.layout.embroidery.export import supported_formats
from stitchswitch.layout.embroidery.machines import load_machines

from fuzzing import FUZZ, byte_edits, check_refusal, json_edits

SEED = resources.files("stitchswitch").joinpath("data/machines.json").read_bytes()


def load(path):
    return load_machines(path, supported_formats())


@FUZZ
@given(text=json_edits(json.loads(SEED)))
def test_json_edits(tmp_path, text):
    path = tmp_path / "machines.json"
    path.write_text(text, encoding="utf-8")
    check_refusal(load, path)


@FUZZ
@given(data=byte_edits(SEED))
def test_byte_edits(tmp_path, data):
    path = tmp_path / "machines.json"
    path.write_bytes(data)
    check_refusal(load, path)
