"""The per-material design-map cache (``reduced.design_space.cache``): keyed and verified by
content; a bad entry is removed and rebuilt with a warning, an unwritable cache only warns."""
import logging
import shutil

import numpy as np
import pytest
from click.testing import CliRunner

from stitchswitch.reduced.design_space import cache, precompute, storage
from stitchswitch.reduced.model.material_io import material_hash, save_material
from stitchswitch.reduced.model.params import DEFAULT_MATERIAL

from helpers import unwritable_dir

OTHER = DEFAULT_MATERIAL.replace(w_b_emb=12.0)
THIRD = DEFAULT_MATERIAL.replace(w_b_emb=11.0)
#: A 3 x 3 grid instead of the real ones, so that each build takes a second.
SMALL = (np.array([30.0, 40.0, 50.0]), np.array([0.7, 0.8, 0.9]))


@pytest.fixture
def small_cache(tmp_path, monkeypatch):
    """A fresh cache folder and 3 x 3 grids; ``builds`` counts the map builds."""
    monkeypatch.setenv("STITCHSWITCH_CACHE", str(tmp_path / "cache"))
    monkeypatch.setattr(cache, "_grid", lambda coarse: SMALL)
    builds = []
    real = precompute.build

    def counted(material, *args, **kw):
        builds.append(material_hash(material))
        return real(material, *args, **kw)
    monkeypatch.setattr(precompute, "build", counted)
    return tmp_path / "cache", builds


def _warnings(caplog):
    return [r.getMessage() for r in caplog.records if r.levelno == logging.WARNING]


def test_a_map_is_built_once_then_read_from_the_cache(small_cache, caplog):
    root, builds = small_cache
    first = cache.map_for(OTHER, coarse=True)
    second = cache.map_for(OTHER, coarse=True)
    assert len(builds) == 1 and np.array_equal(first.h_mm, second.h_mm)
    assert (root / "maps" / f"{material_hash(OTHER)}-coarse.npz").is_file()
    assert _warnings(caplog) == []


@pytest.mark.parametrize("damage", ["truncated", "garbage", "empty", "folder"])
def test_a_corrupt_entry_is_removed_and_rebuilt_with_a_warning(small_cache, caplog, damage):
    root, builds = small_cache
    good = cache.map_for(OTHER, coarse=True)
    path = cache.map_path(OTHER, coarse=True)
    data = path.read_bytes()
    if damage == "folder":
        path.unlink()
        path.mkdir()
        (path / "x").write_text("x")
    else:
        path.write_bytes({"truncated": data[:len(data) // 2], "garbage": b"PK\x03\x04" + b"x" * 99,
                          "empty": b""}[damage])
    rebuilt = cache.map_for(OTHER, coarse=True)
    assert len(builds) == 2 and np.array_equal(rebuilt.h_mm, good.h_mm)
    (message,) = _warnings(caplog)
    assert str(path) in message and "removed, the map is rebuilt" in message
    assert storage.load_map(path).material == OTHER         # the repaired entry is valid
    assert cache.map_for(OTHER, coarse=True) is not None and len(builds) == 2


def test_another_materials_map_under_the_key_is_detected(small_cache, caplog):
    root, builds = small_cache
    cache.map_for(THIRD, coarse=True)
    shutil.copy(cache.map_path(THIRD, coarse=True), cache.map_path(OTHER, coarse=True))
    got = cache.map_for(OTHER, coarse=True)
    assert got.material == OTHER and len(builds) == 2
    (message,) = _warnings(caplog)
    assert "another material" in message and material_hash(THIRD)[:12] in message


def test_a_map_of_another_grid_under_the_key_is_detected(small_cache, caplog, monkeypatch):
    root, builds = small_cache
    cache.map_for(OTHER, coarse=True)
    monkeypatch.setattr(cache, "_grid", lambda coarse: (SMALL[0][:2], SMALL[1]))
    got = cache.map_for(OTHER, coarse=True)
    assert got.diameter_mm.size == 2 and len(builds) == 2
    assert "grid" in _warnings(caplog)[0]


@pytest.mark.parametrize("kind", ["read-only", "a file"])
def test_an_unwritable_cache_only_warns(small_cache, caplog, monkeypatch, tmp_path, kind):
    _, builds = small_cache
    if kind == "a file":
        root = tmp_path / "cachefile"
        root.write_text("not a folder")
    else:
        root = unwritable_dir(tmp_path)
    monkeypatch.setenv("STITCHSWITCH_CACHE", str(root))
    dmap = cache.map_for(OTHER, coarse=True)
    assert dmap.material == OTHER and len(builds) == 1
    (message,) = _warnings(caplog)
    assert str(root) in message and "STITCHSWITCH_CACHE" in message
    if kind == "a file":
        assert (tmp_path / "cachefile").read_text() == "not a folder"


def test_where_the_cache_is(monkeypatch, tmp_path):
    monkeypatch.setenv("STITCHSWITCH_CACHE", str(tmp_path / "a"))
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "x"))
    assert cache.cache_dir() == tmp_path / "a"
    monkeypatch.delenv("STITCHSWITCH_CACHE")
    assert cache.cache_dir() == tmp_path / "x" / "stitchswitch"
    monkeypatch.delenv("XDG_CACHE_HOME")
    monkeypatch.setenv("HOME", str(tmp_path / "home"))
    assert cache.cache_dir() == tmp_path / "home" / ".cache" / "stitchswitch"


MEASURED = """# source: synthetic (test rows)
sample_id,d_mm,fill,h_mm,r_a_mm,z_a_mm,r_b_mm,z_b_mm,split
a,40,0.8,11.73,14.60,5.79,14.68,5.70,train
b,50,0.7,14.62,20.71,6.90,20.73,6.80,val
"""


def test_validate_repairs_a_corrupt_cache_entry(small_cache, tmp_path):
    from stitchswitch.cli.main import cli

    root, builds = small_cache
    data, mat = tmp_path / "d.csv", tmp_path / "m.json"
    data.write_text(MEASURED)
    save_material(OTHER, mat)
    path = cache.map_path(OTHER, coarse=True)
    path.parent.mkdir(parents=True)
    path.write_bytes(b"PK\x05\x06" + b"\x00" * 18)           # an empty zip: not a map
    args = ["validate", str(data), "--material", str(mat), "--json"]
    result = CliRunner().invoke(cli, args + ["--report", str(tmp_path / "r1")])
    assert result.exit_code == 0, result.output
    assert "Traceback" not in result.output and len(builds) == 1
    warning = [line for line in result.stderr.splitlines() if line.startswith("Warning:")]
    assert len(warning) == 1 and str(path) in warning[0]
    result = CliRunner().invoke(cli, args + ["--report", str(tmp_path / "r2")])
    assert result.exit_code == 0 and "Warning" not in result.stderr and len(builds) == 1
