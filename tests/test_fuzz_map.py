"""Fuzzing the design map loader: byte edits of a saved map and edits of its arrays (kind,
shape, values) load or give one short error naming the file, and a map that loads answers
queries anywhere in its domain."""
import tempfile
from pathlib import Path

from hypothesis import given
from hypothesis import strategies as st

from stitchswitch.reduced.design_space import storage

from fuzz_edits import byte_edit, map_edit
from fuzzing import FUZZ, check_refusal, edited
from helpers import synthetic_map


def _saved() -> bytes:
    with tempfile.TemporaryDirectory() as tmp:
        storage.save_map(synthetic_map(), Path(tmp) / "m.npz")
        return (Path(tmp) / "m.npz").read_bytes()


SEED = _saved()


@FUZZ
@given(data=edited(SEED, byte_edit, map_edit, map_edit), d=st.floats(0, 1), p=st.floats(0, 1))
def test_corrupted_copies(tmp_path, data, d, p):
    dmap = check_refusal(storage.load_map, tmp_path / "map.npz", data=data)
    if dmap is not None:
        lo_d, hi_d = dmap.diameter_mm[0], dmap.diameter_mm[-1]
        lo_p, hi_p = dmap.fill[0], dmap.fill[-1]
        q = dmap.query(lo_d + d * (hi_d - lo_d), lo_p + p * (hi_p - lo_p), profiles=True)
        assert q.h_mm.shape == (1,)
