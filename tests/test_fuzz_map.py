"""Fuzzing the design map loader: byte edits of a saved map and edits of its arrays (kind,
shape, values) load or give one short error naming the file, and a map that loads answers
queries anywhere in its domain."""
import io

import numpy as np
from hypothesis import given
from hypothesis import strategies as st

from stitchswitch.reduced.design_space import storage

from fuzzing import FUZZ, byte_edits, check_refusal
from helpers import synthetic_map

_MAP = synthetic_map()


def _saved() -> bytes:
    import tempfile
    from pathlib import Path

    with tempfile.TemporaryDirectory() as tmp:
        storage.save_map(_MAP, Path(tmp) / "m.npz")
        return (Path(tmp) / "m.npz").read_bytes()


SEED = _saved()
with np.load(io.BytesIO(SEED)) as _f:
    ARRAYS = {k: _f[k] for k in _f.files}

REPLACEMENTS = [np.zeros(0), np.zeros((4, 3)), np.zeros((3, 4)), np.zeros((4, 3, 30), np.int32),
                np.full((4, 3), np.nan), np.array(np.inf), np.array("x"), np.array([3.0, 2.0, 1.0, 0.0]),
                np.array([40.0, 40.0, 41.0, 42.0]), np.zeros((4, 3), bool), np.ones(4, np.int64) * 10 ** 6,
                np.array(1e-4), np.full((4, 3), 7, np.int8), np.array(["a", "b"]), np.zeros((2, 2, 2))]


def query_anywhere(dmap, d, p):
    lo_d, hi_d = dmap.diameter_mm[0], dmap.diameter_mm[-1]
    lo_p, hi_p = dmap.fill[0], dmap.fill[-1]
    q = dmap.query(lo_d + d * (hi_d - lo_d), lo_p + p * (hi_p - lo_p), profiles=True)
    assert q.h_mm.shape == (1,)


@FUZZ
@given(data=byte_edits(SEED), d=st.floats(0, 1), p=st.floats(0, 1))
def test_byte_edits(tmp_path, data, d, p):
    path = tmp_path / "map.npz"
    path.write_bytes(data)
    dmap = check_refusal(storage.load_map, path)
    if dmap is not None:
        query_anywhere(dmap, d, p)


@FUZZ
@given(edits=st.lists(st.tuples(st.sampled_from(sorted(ARRAYS)),
                                st.sampled_from(range(-1, len(REPLACEMENTS)))), min_size=1,
                      max_size=3),
       d=st.floats(0, 1), p=st.floats(0, 1))
def test_array_edits(tmp_path, edits, d, p):
    arrays = dict(ARRAYS)
    for name, k in edits:
        if k < 0:
            arrays.pop(name, None)
        else:
            arrays[name] = REPLACEMENTS[k]
    path = tmp_path / "map.npz"
    with open(path, "wb") as f:
        np.savez_compressed(f, **arrays)
    dmap = check_refusal(storage.load_map, path)
    if dmap is not None:
        query_anywhere(dmap, d, p)
