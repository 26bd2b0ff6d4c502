"""Fuzzing the machine catalogue loader (``--machines``): structured edits and byte edits of the
shipped catalogue load or give one short error naming the file."""
from importlib import resources

from hypothesis import given

from stitchswitch.layout.embroidery.export import supported_formats
from stitchswitch.layout.embroidery.machines import load_machines

from fuzz_edits import byte_edit, json_edit
from fuzzing import FUZZ, check_refusal, edited

SEED = resources.files("stitchswitch").joinpath("data/machines.json").read_bytes()


@FUZZ
@given(data=edited(SEED, byte_edit, json_edit, json_edit))
def test_corrupted_copies(tmp_path, data):
    check_refusal(lambda p: load_machines(p, supported_formats()), tmp_path / "machines.json", data=data)
