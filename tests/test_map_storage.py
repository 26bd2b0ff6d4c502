"""The map file's loader checks everything a query relies on: each corruption is one
``InvalidInputError`` naming the file, and a map that loads answers every query."""
import io
import struct
import zipfile

import numpy as np
import pytest

from stitchswitch.errors import InvalidInputError
from stitchswitch.reduced.design_space import storage

from helpers import synthetic_map


@pytest.fixture
def saved(tmp_path):
    path = tmp_path / "m.npz"
    storage.save_map(synthetic_map(), path)
    return path


def arrays(path) -> dict:
    with np.load(path) as f:
        return {k: f[k] for k in f.files}


def rewrite(path, **changes):
    data = arrays(path)
    data.update(changes)
    data = {k: v for k, v in data.items() if v is not None}
    buf = io.BytesIO()
    np.savez_compressed(buf, **data)
    path.write_bytes(buf.getvalue())


def refused(path) -> str:
    with pytest.raises(InvalidInputError) as info:
        storage.load_map(path)
    message = str(info.value)
    assert message.startswith(f"design map {str(path)!r}: ") and len(message) < 300
    return message


def test_round_trip_and_query(saved):
    dmap = storage.load_map(saved)
    q = dmap.query([40.5, 42.0], [0.72, 0.8], profiles=True)
    assert np.allclose(q.h_mm, 0.1 * np.array([40.5, 42.0]) + [0.72, 0.8])
    assert np.all(np.isfinite(q.z_mm))


@pytest.mark.parametrize("cut", [100, 1000, 5000, -200, -22])
def test_truncated_file(saved, cut):
    saved.write_bytes(saved.read_bytes()[:cut])
    assert "cannot be read as a .npz file" in refused(saved)


def test_corrupt_compressed_stream(saved):
    raw = bytearray(saved.read_bytes())
    with zipfile.ZipFile(saved) as z:
        info = z.getinfo("h_mm.npy")
    name_len, extra_len = struct.unpack("<HH", raw[info.header_offset + 26:info.header_offset + 30])
    start = info.header_offset + 30 + name_len + extra_len + 10
    raw[start:start + 8] = b"\xff" * 8                         # inside the deflate stream
    saved.write_bytes(bytes(raw))
    assert "cannot be read as a .npz file" in refused(saved)


@pytest.mark.parametrize("changes, message", [
    ({"format": None}, "not a stitchswitch-design-map-1 file"),
    ({"format": np.array([1, 2])}, "not a stitchswitch-design-map-1 file"),
    ({"h_mm": None}, "missing array(s) h_mm"),
    ({"h_mm": np.array([["a"]])}, "h_mm has dtype <U1, expected floats"),
    ({"converged": np.zeros((4, 3))}, "converged has dtype float64, expected booleans"),
    ({"u_mm": np.zeros((4, 3, 30))}, "u_mm has dtype float64, expected signed integers"),
    ({"h_mm": np.zeros((3, 4))}, "h_mm has shape (3, 4), expected (4, 3)"),
    ({"z_mm": np.zeros((4, 3, 29), np.int32)}, "z_mm has shape (4, 3, 29), expected (4, 3, 30)"),
    ({"diameter_mm": np.array([40.0, 42.0, 41.0, 43.0])}, "diameter_mm is not a strictly "
                                                          "increasing grid"),
    ({"fill": np.array([0.7, np.nan, 0.8])}, "fill is not a strictly increasing grid"),
    ({"r_a_mm": np.full((4, 3), np.inf)}, "r_a_mm holds a value that is not finite"),
    ({"dr_mm": np.zeros(4)}, "dr_mm holds a node spacing <= 0"),
    ({"n_inside": np.full(4, 30)}, "n_inside holds a boundary node outside [1, 29]"),
    ({"flags": np.full((4, 3), 9, np.int8)}, "flags holds a code that is not one of"),
    ({"material_hash": np.array("0" * 64)}, "the material hash does not match"),
    ({"material_json": np.array("{")}, "material: not valid JSON"),
    ({"profile_quantum_mm": np.array(1.0)}, "unsupported profile quantum 1"),
])
def test_corrupted_arrays(saved, changes, message):
    rewrite(saved, **changes)
    assert message in refused(saved)


def test_a_one_point_grid_is_refused(tmp_path):
    path = tmp_path / "m.npz"
    storage.save_map(synthetic_map(nd=1), path)
    assert "the grid is 1 x 3 designs" in refused(path)


def test_declared_size_is_bounded(saved, monkeypatch):
    monkeypatch.setattr(storage, "MAX_MAP_BYTES", 1000)
    assert "more than the limit" in refused(saved)


def test_the_issue_reproducer_through_the_cli(saved, tmp_path):
    from click.testing import CliRunner

    from stitchswitch.cli.main import cli

    bad = tmp_path / "t.npz"
    bad.write_bytes(saved.read_bytes()[:1000])
    r = CliRunner().invoke(cli, ["inverse", "--height", "10", "--map", str(bad)])
    assert r.exit_code == 2 and r.output.startswith("Error: design map ")
    assert r.output.count("\n") == 1 and "Traceback" not in r.output
