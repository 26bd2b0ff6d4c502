"""Material files: round trip, canonical bytes, hash, and one clear message per error."""
import hashlib
import json
import os

import pytest

from stitchswitch.errors import InvalidInputError
from stitchswitch.reduced.model.material_io import (
    canonical_json,
    default_material_path,
    load_material,
    material_hash,
    save_material,
)
from stitchswitch.reduced.model.params import DEFAULT_MATERIAL, Material

OTHER = DEFAULT_MATERIAL.replace(w_b_fab=0.123456789012345, n_nodes=400, eta=1.5)


def write(path, obj):
    if isinstance(obj, dict):                    # a value ... drops the key
        obj = {k: v for k, v in obj.items() if v is not ...}
    path.write_text(obj if isinstance(obj, str) else json.dumps(obj))
    return path


def required(material=DEFAULT_MATERIAL):
    keys = ("w_b_emb", "w_b_fab", "k_r_emb", "k_r_fab", "k_theta_emb", "k_theta_fab", "w_log")
    return {k: getattr(material, k) for k in keys}


@pytest.mark.parametrize("material", [DEFAULT_MATERIAL, OTHER])
def test_round_trip(tmp_path, material):
    save_material(material, tmp_path / "m.json")
    assert load_material(tmp_path / "m.json") == material
    assert load_material(str(tmp_path / "m.json")) == material


def test_identical_materials_give_identical_bytes(tmp_path):
    twin = Material(**OTHER.as_dict())
    save_material(OTHER, tmp_path / "a.json")
    save_material(twin, tmp_path / "b.json")
    save_material(load_material(tmp_path / "a.json"), tmp_path / "c.json")
    a = (tmp_path / "a.json").read_bytes()
    assert a == (tmp_path / "b.json").read_bytes() == (tmp_path / "c.json").read_bytes()
    assert a.endswith(b"\n") and list(json.loads(a)) == sorted(json.loads(a))
    assert sorted(os.listdir(tmp_path)) == ["a.json", "b.json", "c.json"]


def test_hash_is_sha256_of_the_saved_file_and_stable(tmp_path):
    save_material(OTHER, tmp_path / "m.json")
    digest = hashlib.sha256((tmp_path / "m.json").read_bytes()).hexdigest()
    assert material_hash(OTHER) == digest == material_hash(Material(**OTHER.as_dict()))
    assert material_hash(load_material(tmp_path / "m.json")) == digest
    assert material_hash(DEFAULT_MATERIAL) != digest
    assert len(digest) == 64


def test_optional_fields_take_defaults(tmp_path):
    loaded = load_material(write(tmp_path / "m.json", required()))
    assert loaded == Material(**required())
    assert loaded.k_r_emb == DEFAULT_MATERIAL.k_r_emb and loaded.label == ""


def test_shipped_default_material_equals_default():
    path = default_material_path()
    assert load_material(path) == DEFAULT_MATERIAL
    assert path.read_text(encoding="utf-8") == canonical_json(DEFAULT_MATERIAL)


def _error(path):
    with pytest.raises(InvalidInputError) as info:
        load_material(path)
    message = str(info.value)
    assert "\n" not in message and str(path) in message
    return message


@pytest.mark.parametrize("content, expected", [
    ({**required(), "colour": 1}, "$.colour: unknown key (allowed: w_b_emb, w_b_fab"),
    ({**required(), "colour": 1, "size": 2}, "$.colour: unknown key (allowed: w_b_emb, w_b_fab"),
    ({**required(), "colour": 1, "size": 2}, "; also unknown: 'size'"),
    ({**required(), "w_logg": 1.0, "w_log": ...}, "$.w_logg: unknown key (allowed: "),
    ({**required(), "w_logg": 1.0, "w_log": ...}, "; did you mean 'w_log'?"),
    ({k: v for k, v in required().items() if k != "w_log"}, "$.w_log: missing"),
    ({"w_log": 1.0}, "$.w_b_emb: missing (also missing: 'w_b_fab', 'k_r_emb', 'k_r_fab', "
                     "'k_theta_emb', 'k_theta_fab')"),
    ({**required(), "k_r_emb": -1.0}, "$.k_r_emb: -1.0 must be > 0"),
    ({**required(), "eta": 5}, "$.eta: 5.0 is outside (1, 3]"),
    ({**required(), "n_nodes": 2.5}, "$.n_nodes: 2.5 is not an integer"),
    ({**required(), "w_b_emb": "1.0"}, "$.w_b_emb: '1.0' is not a number"),
    ({**required(), "w_b_emb": True}, "$.w_b_emb: true is not a number"),
    ({**required(), "w_b_emb": None}, "$.w_b_emb: null is not a number"),
    ({**required(), "w_b_emb": [1.0]}, "$.w_b_emb: [1.0] is not a number"),
    (json.dumps({**required(), "w_b_emb": float("nan")}),
     "$.w_b_emb: NaN is not a finite number (JSON has no NaN or Infinity)"),
    ([1, 2], "$: a material (an object of material fields) must be a JSON object, got an array"),
    ('{"w_b_emb": 1.0,', "not valid JSON (Expecting property name enclosed in double quotes at "
                         "line 1, column 17)"),
    ('{"w_b_emb": 1.0, "w_b_emb": 2.0}', "$.w_b_emb: duplicate key"),
])
def test_errors_name_the_file_and_the_field(tmp_path, content, expected):
    assert expected in _error(write(tmp_path / "m.json", content))


def test_unreadable_file(tmp_path):
    assert "cannot be read" in _error(tmp_path / "missing.json")
    (tmp_path / "dir.json").mkdir()
    assert "cannot be read" in _error(tmp_path / "dir.json")
    (tmp_path / "bin.json").write_bytes(b"\xff\xfe{}")
    assert "UTF-8" in _error(tmp_path / "bin.json")


def test_save_rejects_non_material(tmp_path):
    with pytest.raises(TypeError):
        save_material({"w_log": 1.0}, tmp_path / "m.json")
    assert os.listdir(tmp_path) == []
