"""Fuzzing the design-map cache: whatever bytes sit under a cache key (a corrupted copy of a
valid entry), reading the cache never raises: it returns the very map asked for, or removes
the entry with one warning and returns None (the caller then rebuilds it)."""
import logging
import tempfile
from pathlib import Path

import numpy as np
from hypothesis import given

from stitchswitch.reduced.design_space import cache, storage
from stitchswitch.reduced.model.params import DEFAULT_MATERIAL

from fuzz_edits import byte_edit, map_edit
from fuzzing import FUZZ, edited
from helpers import synthetic_map

MAP = synthetic_map()
#: The key of a material other than the default (the default's map ships and is never cached).
OTHER = DEFAULT_MATERIAL.replace(w_b_emb=12.0)


def _saved() -> bytes:
    from dataclasses import replace

    from stitchswitch.reduced.model.material_io import material_hash

    with tempfile.TemporaryDirectory() as tmp:
        storage.save_map(replace(MAP, material=OTHER, material_hash=material_hash(OTHER)),
                         Path(tmp) / "m.npz")
        return (Path(tmp) / "m.npz").read_bytes()


SEED = _saved()


@FUZZ
@given(data=edited(SEED, byte_edit, map_edit))
def test_a_corrupted_entry_is_used_only_if_it_is_the_map(tmp_path, monkeypatch, caplog, data):
    monkeypatch.setenv("STITCHSWITCH_CACHE", str(tmp_path / "cache"))
    monkeypatch.setattr(cache, "_grid", lambda coarse: (MAP.diameter_mm, MAP.fill))
    path = cache.map_path(OTHER, coarse=True)
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_bytes(data)
    caplog.clear()
    with caplog.at_level(logging.WARNING):
        dmap = cache.cached_map(OTHER, coarse=True)
    warnings = [r for r in caplog.records if r.levelno == logging.WARNING]
    if dmap is None:
        assert len(warnings) == 1 and str(path) in warnings[0].getMessage()
        assert not path.exists()
    else:
        assert warnings == [] and dmap.material == OTHER
        assert np.array_equal(dmap.diameter_mm, MAP.diameter_mm)
        assert np.array_equal(dmap.fill, MAP.fill)
