"""The design file: round trip, canonical bytes, every validation error by JSON path, schema."""
import copy
import json
import pathlib
import re

import numpy as np
import pytest

from stitchswitch.errors import InvalidInputError
from stitchswitch.layout.garment.design import (
    CompositeSpec,
    Design,
    MachineSpec,
    MaterialRef,
    PatchSpec,
    PieceSpec,
    Threads,
)
from stitchswitch.layout.garment.design_io import (
    design_from_dict,
    design_to_dict,
    dumps_design,
    load_design,
    save_design,
)
from stitchswitch.reduced.model.material_io import save_material
from stitchswitch.reduced.model.params import DEFAULT_MATERIAL

ROOT = pathlib.Path(__file__).resolve().parents[1]
SCHEMA = ROOT / "src/stitchswitch/data/design.schema.json"
DOC = ROOT / "docs/design-file.md"


def base() -> dict:
    """A valid design file object with one plain and one composite, shaped patch."""
    return {
        "version": 1,
        "pieces": [{"name": "front", "size": "M", "source": "tank.dxf",
                    "outline_mm": [[0, 0], [300, 0], [300, 200], [0, 200]]},
                   {"name": "back", "size": "M", "source": "tank.dxf",
                    "outline_mm": [[0, 0], [100, 0], [50, 80]]}],
        "patches": [
            {"id": "p1", "piece": "front", "centre_mm": [150, 100], "diameter_mm": 40, "fill": 0.8},
            {"id": "p2", "piece": "front", "centre_mm": [60.5, 50.25], "diameter_mm": 60.0,
             "fill": 0.5, "composite": {"core_diameter_mm": 20, "core_fill": 1.0},
             "outline_mm": [[-22, -18], [22, -18], [22, 18], [-22, 18]],
             "conductive": "ring:0", "threads": {"top": "#FF0000", "conductive": "#b0b0b0"},
             "state": "down"}],
        "material": {"name": "default"},
        "machine": {"name": "janome-550e", "hoop": "sq20B"},
    }


def test_build_and_fields():
    d = design_from_dict(base())
    assert [p.name for p in d.pieces] == ["front", "back"]
    p1, p2 = d.patches
    assert p1 == PatchSpec("p1", "front", (150.0, 100.0), 40.0, 0.8)
    assert p1.composite is None and p1.outline_mm is None and p1.threads == Threads()
    assert p2.composite == CompositeSpec(20.0, 1.0) and p2.state == "down"
    assert p2.threads.top == "#ff0000"                      # colours are normalised
    assert p2.outline_mm.shape == (4, 2) and not p2.outline_mm.flags.writeable
    assert d.machine == MachineSpec("janome-550e", "SQ20b")  # canonical hoop spelling
    assert d.material == MaterialRef("default", None)
    assert d.piece("back").outline_mm.shape == (3, 2)
    with pytest.raises(InvalidInputError, match="no piece named 'side'; the pieces are front, back"):
        d.piece("side")
    assert d.material_object() == DEFAULT_MATERIAL


def test_round_trip_bytes_and_equality(tmp_path):
    obj = base()
    kept = copy.deepcopy(obj)
    d = design_from_dict(obj)
    assert obj == kept                                      # input not mutated
    path = tmp_path / "d.json"
    save_design(d, path)
    text = path.read_text()
    loaded = load_design(path)
    assert loaded == d and loaded.path == str(path)
    save_design(loaded, tmp_path / "again.json")
    assert (tmp_path / "again.json").read_text() == text    # byte-identical
    assert text.endswith("}\n") and "\n  \"pieces\": [\n" in text
    keys = list(json.loads(text))
    assert keys == ["version", "pieces", "patches", "material", "machine"]
    assert list(json.loads(text)["patches"][1]) == [
        "id", "piece", "centre_mm", "diameter_mm", "fill", "composite", "outline_mm",
        "conductive", "threads", "state"]
    assert "        [300.0, 200.0],\n" in text                # one point per line


def test_floats_rounded_to_micrometres():
    d = design_from_dict(base())
    p = d.patches[0].replace(centre_mm=(1 / 3, -1e-9), fill=2 / 3)
    text = dumps_design(d.with_patches([p]))
    assert '"centre_mm": [0.333333, 0.0]' in text and '"fill": 0.666667' in text
    again = design_from_dict(json.loads(text))
    assert dumps_design(again) == text


def test_defaults_and_repeated_first_point():
    obj = base()
    del obj["material"], obj["machine"]
    obj["pieces"][0]["outline_mm"].append([0, 0])            # closed ring written out
    del obj["pieces"][0]["size"], obj["pieces"][0]["source"]
    d = design_from_dict(obj)
    assert d.material == MaterialRef() and d.machine == MachineSpec()
    assert d.pieces[0].outline_mm.shape == (4, 2) and d.pieces[0].size == ""


def test_design_objects_built_in_code_equal_loaded():
    piece = PieceSpec("front", "M", "tank.dxf", [[0, 0], [300, 0], [300, 200], [0, 200]])
    arr = np.array([[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]])
    other = PieceSpec("front", "M", "tank.dxf", arr)
    arr[0, 0] = 5.0                                           # the spec holds a copy
    assert other.outline_mm[0, 0] == 0.0
    d = Design(1, [piece], [PatchSpec("p1", "front", (150, 100), 40, 0.8)])
    assert d == design_from_dict(design_to_dict(d))
    assert d != d.with_patches([])


def test_save_is_atomic_and_refuses_invalid(tmp_path):
    path = tmp_path / "d.json"
    d = design_from_dict(base())
    save_design(d, path)
    before = path.read_bytes()
    bad = d.with_patches([d.patches[0].replace(fill=1.4)])
    with pytest.raises(InvalidInputError, match=r"patches\[0\].fill: 1.4 is outside \(0, 1\]"):
        save_design(bad, path)
    assert path.read_bytes() == before
    assert sorted(p.name for p in tmp_path.iterdir()) == ["d.json"]   # no temporary left


def _set(obj, path, value):
    """Set (or delete, value=...) the item at a JSON path like patches[1].composite.core_fill."""
    parts = re.findall(r"[^.\[\]]+|\[\d+\]", path)
    target = obj
    for part in parts[:-1]:
        target = target[int(part[1:-1])] if part.startswith("[") else target[part]
    last = parts[-1]
    key = int(last[1:-1]) if last.startswith("[") else last
    if value is ...:
        del target[key]
    else:
        target[key] = value


CASES = [
    ("patches[1].fill", 1.4, "$.patches[1].fill: 1.4 is outside (0, 1]"),
    ("patches[0].fill", 0, "$.patches[0].fill: 0 is outside (0, 1]"),
    ("patches[0].fill", "0.8", "$.patches[0].fill: '0.8' is not a number in (0, 1]"),
    ("patches[0].fill", True, "$.patches[0].fill: true is not a number in (0, 1]"),
    ("patches[0].fill", ..., "$.patches[0].fill: missing"),
    ("patches[0].diameter_mm", 2, "$.patches[0].diameter_mm: 2 is outside [5, 360] mm"),
    ("patches[0].centre_mm", [1, 2, 3], "$.patches[0].centre_mm: must be a pair [x, y]"),
    ("patches[0].centre_mm", [1, None], "$.patches[0].centre_mm[1]: null is not a number"),
    ("patches[0].piece", "sleeve", "$.patches[0].piece: 'sleeve' is not a piece of this design "
                                   "(pieces: front, back)"),
    ("patches[1].id", "p1", "$.patches[1].id: 'p1' is already the id of $.patches[0]"),
    ("patches[0].id", "", "$.patches[0].id: must not be empty"),
    ("patches[0].colour", "red", "$.patches[0].colour: unknown key"),
    ("patches[0].state", "sideways", "$.patches[0].state: 'sideways' is not one of 'up', 'down'"),
    ("patches[0].conductive", "blob:1", "$.patches[0].conductive: unknown selection 'blob:1'"),
    ("patches[0].conductive", "ring:x", "$.patches[0].conductive: cannot read the selection"),
    ("patches[0].threads", {"top": "black"}, "$.patches[0].threads.top: 'black' is not a colour"),
    ("patches[0].threads", {"bobbin": "#000000"}, "$.patches[0].threads.bobbin: unknown key"),
    ("patches[0].threads", [], "$.patches[0].threads: must be an object, got an array"),
    ("patches[1].composite.core_diameter_mm", 60,
     "$.patches[1].composite.core_diameter_mm: 60 is outside (0, 60) mm (the patch diameter)"),
    ("patches[1].composite.core_fill", 1.2, "$.patches[1].composite.core_fill: 1.2 is outside (0, 1]"),
    ("patches[1].composite.core_fill", ..., "$.patches[1].composite.core_fill: missing"),
    ("patches[1].composite", None,
     "$.patches[1].outline_mm: a custom outline needs $.patches[1].composite"),
    ("patches[1].outline_mm[2]", [25, 25],
     "$.patches[1].outline_mm[2]: [25.0, 25.0] lies 35.3553 mm from the centre, outside the "
     "patch radius 30 mm"),
    ("patches[1].outline_mm", [[-20, -20], [20, 20], [20, -20], [-20, 20]],
     "$.patches[1].outline_mm: is not a simple polygon (Self-intersection"),
    ("patches[1].outline_mm", [[-8, -20], [8, -20], [8, 20], [-8, 20]],
     "$.patches[1].outline_mm: the core disc (diameter 20 mm) is not inside the outline "
     "(closest outline point 8 mm from the centre)"),
    ("patches[1].outline_mm", [[5, 5], [25, 5], [25, 15]],
     "$.patches[1].outline_mm: does not contain the centre"),
    ("patches[1].outline_mm", [[0, 0], [1, 1]], "$.patches[1].outline_mm: needs at least 3 points"),
    ("patches", {}, "$.patches: must be an array, got an object"),
    ("pieces[1].name", "front", "$.pieces[1].name: 'front' is already the name of $.pieces[0]"),
    ("pieces[0].name", 7, "$.pieces[0].name: must be a string, got a number (7)"),
    ("pieces[0].outline_mm", [[0, 0], [1, 0]], "$.pieces[0].outline_mm: needs at least 3 distinct"),
    ("pieces[0].outline_mm", [[0, 0], [1, 0], [2, 0]], "$.pieces[0].outline_mm: encloses no area"),
    ("pieces[0].outline_mm[1]", [300], "$.pieces[0].outline_mm[1]: must be a pair [x, y]"),
    ("pieces", ..., "$.pieces: missing"),
    ("version", 2, "$.version: 2 is not a supported design file version (this stitchswitch "
                   "reads version 1)"),
    ("version", "1", "$.version: '1' is not a supported design file version"),
    ("version", ..., "$.version: missing (this stitchswitch reads version 1)"),
    ("colour", "red", "$.colour: unknown key (allowed: version, pieces, patches, material, machine, blank_margin_mm)"),
    ("material", {"name": "default", "file": "m.json"},
     "$.material: give exactly one of 'name' (a built-in material) or 'file'"),
    ("material", {"name": "silk"}, "$.material.name: 'silk' is not a built-in material"),
    ("machine", {"name": "brother-pe800"}, "$.machine.name: unknown machine 'brother-pe800' "
                                           "(machines: janome-550e"),
    ("machine", {"hoop": "XL99"}, "$.machine.hoop: 'XL99' is not a hoop of the janome-550e "
                                  "(hoops: SQ14b, RE20b, SQ20b, RE36b)"),
    ("machine", {"hoop": 5}, "$.machine.hoop: must be a string, got a number (5)"),
    ("machine", [], "$.machine: must be an object, got an array"),
    ("patches[0].centre_mm", [1, float("nan")], "$.patches[0].centre_mm[1]: NaN is not a finite number"),
]


@pytest.mark.parametrize("path,value,message", CASES, ids=[c[0] + ":" + str(c[1])[:20] for c in CASES])
def test_validation_error_names_the_json_path(path, value, message):
    obj = base()
    _set(obj, path, value)
    with pytest.raises(InvalidInputError) as exc:
        design_from_dict(obj, "design file 'x.json'")
    assert str(exc.value).startswith("design file 'x.json': ")
    assert message in str(exc.value)


def test_machine_from_the_catalogue_in_its_own_spelling():
    obj = base()
    obj["machine"] = {"name": "JANOME-550E", "hoop": "re36B"}
    assert design_from_dict(obj).machine == MachineSpec("janome-550e", "RE36b")


def test_not_an_object():
    with pytest.raises(InvalidInputError, match=r"\$: a design must be a JSON object, got an array"):
        design_from_dict([])


@pytest.mark.parametrize("text,message", [
    ('{"version": 1, "version": 1}', "$.version: duplicate key"),
    ('{"version": 1, "pieces": [], "patches": [], "x": NaN}', "$.x: NaN is not a finite number"),
    ('{"version": 1, "pieces": [{"name": "a", "outline_mm": [[0, 0], [1, 0], [0, Infinity]]}]}',
     "$.pieces[0].outline_mm[2][1]: Infinity is not a finite number"),
    ('{"version": 1, "pieces": [], "patches": [{"id": "p", "id": "q"}]}', "$.patches[0].id: duplicate key"),
    ('{"version": 1,', "not valid JSON"),
])
def test_file_level_errors(tmp_path, text, message):
    path = tmp_path / "d.json"
    path.write_text(text)
    with pytest.raises(InvalidInputError) as exc:
        load_design(path)
    assert str(exc.value).startswith(f"design file {str(path)!r}: ") and message in str(exc.value)


def test_missing_file(tmp_path):
    with pytest.raises(InvalidInputError, match="cannot be read"):
        load_design(tmp_path / "none.json")


def test_material_file_relative_to_the_design(tmp_path):
    (tmp_path / "mats").mkdir()
    mat = DEFAULT_MATERIAL.replace(eta=1.5)
    save_material(mat, tmp_path / "mats" / "m.json")
    obj = base()
    obj["material"] = {"file": "mats/m.json"}
    path = tmp_path / "d.json"
    path.write_text(json.dumps(obj))
    d = load_design(path)
    assert d.material == MaterialRef(None, "mats/m.json") and d.material_object() == mat
    obj["material"] = {"file": "mats/none.json"}
    path.write_text(json.dumps(obj))
    with pytest.raises(InvalidInputError, match=r"material.file: material file .*none.json.*cannot be read"):
        load_design(path)


def _doc_examples() -> list:
    blocks = re.findall(r"```json\n(.*?)```", DOC.read_text(), flags=re.S)
    return [json.loads(b) for b in blocks if '"version"' in b]


def test_documented_example_loads():
    examples = _doc_examples()
    assert examples, "docs/design-file.md has no JSON example"
    for obj in examples:
        design_from_dict(obj, "docs example")


def test_schema_accepts_the_examples_and_rejects_bad_values():
    schema = json.loads(SCHEMA.read_text())
    assert set(schema["required"]) == {"version", "pieces", "patches"}
    assert set(schema["properties"]) == {"version", "pieces", "patches", "material", "machine",
                                         "blank_margin_mm"}
    import jsonschema  # in the test extra: never skipped
    jsonschema.Draft202012Validator.check_schema(schema)
    validator = jsonschema.Draft202012Validator(schema)
    for obj in [base(), *_doc_examples(), design_to_dict(design_from_dict(base()))]:
        assert not list(validator.iter_errors(obj))
    for path, value, _ in CASES:
        if path in ("patches[1].fill", "version", "colour", "patches[0].state"):
            obj = base()
            _set(obj, path, value)
            assert list(validator.iter_errors(obj)), path


@pytest.mark.parametrize("where, value, message", [
    ("patches[0].centre_mm[0]", 10 ** 400, "$.patches[0].centre_mm[0]: 1000"),
    ("patches[0].diameter_mm", 10 ** 400, "$.patches[0].diameter_mm: 1000"),
    ("patches[0].id", "p" * 5000, "is 5000 characters long, more than 100"),
    ("patches[0].piece", "q" * 5000, "$.patches[0].piece: 'qqq"),
])
def test_huge_values_are_one_short_message(tmp_path, where, value, message):
    """An integer beyond the float range or a 5,000-character name: one short message, not an
    OverflowError or the whole value."""
    obj = base()
    _set(obj, where, value)
    path = tmp_path / "d.json"
    path.write_text(json.dumps(obj))
    with pytest.raises(InvalidInputError) as info:
        load_design(path)
    assert message in str(info.value) and len(str(info.value)) < 300
