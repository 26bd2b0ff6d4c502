"""The shared JSON checks (``files.json_checks``): every check returns the checked value, and
every error names the JSON path of the bad value (and, through ``reporting``, the file)."""
import math

import pytest

from stitchswitch.errors import InvalidInputError
from stitchswitch.files import json_checks as jc
from stitchswitch.files.json_checks import JsonError


def error(check, *args, **kwargs) -> JsonError:
    with pytest.raises(JsonError) as info:
        check(*args, **kwargs)
    return info.value


def test_child_paths():
    assert jc.child("$", "patches") == "$.patches"
    assert jc.child("$.patches", 2) == "$.patches[2]"
    assert jc.child("$.patches[2]", "diameter_mm") == "$.patches[2].diameter_mm"
    assert jc.child("$", "a key") == '$["a key"]' and jc.child("$", "1st") == '$["1st"]'
    assert jc.child("$", True) == "$.True"                  # a boolean is no array index


def test_show_and_kind():
    assert [jc.show(v) for v in ("abc", True, False, None, 1.5, 2, [1, "a"], {"k": None})] == [
        "'abc'", "true", "false", "null", "1.5", "2", '[1, "a"]', '{"k": null}']
    assert [jc.show(v) for v in (math.nan, math.inf, -math.inf)] == ["NaN", "Infinity", "-Infinity"]
    long = jc.show(list(range(100)))
    assert len(long) == 60 and long.endswith("...")
    assert [jc.kind(v) for v in ({}, [], "", True, 1, 1.0, None)] == [
        "an object", "an array", "a string", "a boolean", "a number", "a number", "null"]


def test_reporting_adds_the_file_and_at_adds_the_path():
    with pytest.raises(InvalidInputError) as info:
        with jc.reporting("design file 'design.json'"):
            jc.number(-3, "$.patches[2].diameter_mm", low=5, high=360, unit="mm")
    assert str(info.value) == ("design file 'design.json': $.patches[2].diameter_mm: "
                               "-3 is outside [5, 360] mm")
    with pytest.raises(JsonError) as info:
        with jc.at("$.patches[0].conductive"):
            raise InvalidInputError("unknown selection 'blob:1'")
    assert (info.value.path, info.value.message) == ("$.patches[0].conductive",
                                                     "unknown selection 'blob:1'")
    assert str(error(jc.fail, "$.x", "bad")) == "$.x: bad"


# --- parsing ------------------------------------------------------------------------------

def test_loads_parses_plain_json():
    assert jc.loads('{"a": [1, 2.5, "x", true, null], "b": {}}', "f") == {
        "a": [1, 2.5, "x", True, None], "b": {}}
    assert jc.loads("[]", "f") == [] and type(jc.loads('{"a": 1}', "f")) is dict


@pytest.mark.parametrize("text, message", [
    ('{"a": 1, "a": 2}', "f.json: $.a: duplicate key"),
    ('{"a": {"b": [0, {"c": 1, "c": 1}]}}', "f.json: $.a.b[1].c: duplicate key"),
    ('{"a": NaN}', "f.json: $.a: NaN is not a finite number (JSON has no NaN or Infinity)"),
    ('{"a": [1, -Infinity]}', "f.json: $.a[1]: -Infinity is not a finite number"),
    ("Infinity", "f.json: $: Infinity is not a finite number"),
    ('{"a": 1,', "f.json: not valid JSON (Expecting property name enclosed in double quotes at "
                "line 1, column 9)"),
    ("", "f.json: not valid JSON (Expecting value at line 1, column 1)"),
])
def test_loads_refuses_duplicates_constants_and_bad_json(text, message):
    with pytest.raises(InvalidInputError) as info:
        jc.loads(text, "f.json")
    assert str(info.value).startswith(message)


def test_load_file(tmp_path):
    path = tmp_path / "f.json"
    path.write_text('\ufeff{"a": [1]}', encoding="utf-8")       # a byte-order mark is dropped
    assert jc.load_file(path, "f") == {"a": [1]}
    with pytest.raises(InvalidInputError, match="^f: cannot be read"):
        jc.load_file(tmp_path / "none.json", "f")
    path.write_text('{"a": 1, "a": 1}')
    with pytest.raises(InvalidInputError, match=r"^f: \$.a: duplicate key"):
        jc.load_file(path, "f")


# --- containers ---------------------------------------------------------------------------

def test_obj_accepts_and_returns_the_object():
    value = {"a": 1, "b": 2}
    assert jc.obj(value, "$", required=("a",), optional=("b", "c")) is value


@pytest.mark.parametrize("value, kwargs, path, message", [
    ([], {}, "$.m", "must be an object, got an array"),
    ("x", {"what": "a design"}, "$.m", "a design must be a JSON object, got a string ('x')"),
    ({"a": 1, "zz": 2}, {"required": ("a",), "optional": ("b",)}, "$.m.zz",
     "unknown key (allowed: a, b)"),
    ({"a": 1, "zz": 2, "yy": 3}, {"required": ("a",)}, "$.m.zz",
     "unknown key (allowed: a); also unknown: 'yy'"),
    ({"fil": 1}, {"required": ("fill", "id")}, "$.m.fil",
     "unknown key (allowed: fill, id); did you mean 'fill'?"),
    ({"b": 1}, {"required": ("a",), "optional": ("b",)}, "$.m.a", "missing"),
    ({}, {"required": ("a", "b", "c")}, "$.m.a", "missing (also missing: 'b', 'c')"),
    ({"x y": 1}, {}, '$.m["x y"]', "unknown key (allowed: )"),
])
def test_obj_errors_name_the_key(value, kwargs, path, message):
    e = error(jc.obj, value, "$.m", **kwargs)
    assert (e.path, e.message) == (path, message)


def test_array_and_items():
    assert jc.array([1], "$.a") == [1] and jc.array([], "$.a") == []
    e = error(jc.array, {}, "$.a")
    assert (e.path, e.message) == ("$.a", "must be an array, got an object")
    e = error(jc.array, [], "$.a", nonempty=True)
    assert (e.path, e.message) == ("$.a", "must be a non-empty array, got an empty one")
    e = error(jc.array, 3, "$.a", nonempty=True)
    assert (e.path, e.message) == ("$.a", "must be a non-empty array, got a number (3)")
    assert jc.items([1, 2], "$.a", lambda v, p: (v, p)) == [(1, "$.a[0]"), (2, "$.a[1]")]
    e = error(jc.items, [1, "two"], "$.a", jc.number)
    assert (e.path, e.message) == ("$.a[1]", "'two' is not a number")
    e = error(jc.items, [], "$.a", jc.number, nonempty=True)
    assert e.path == "$.a"


# --- scalars ------------------------------------------------------------------------------

def test_text():
    assert jc.text("a", "$.s") == "a" and jc.text("", "$.s") == ""
    e = error(jc.text, 7, "$.s")
    assert (e.path, e.message) == ("$.s", "must be a string, got a number (7)")
    e = error(jc.text, None, "$.s")
    assert (e.path, e.message) == ("$.s", "must be a string, got null")
    e = error(jc.text, "  ", "$.s", nonempty=True)
    assert (e.path, e.message) == ("$.s", "must not be empty")


def test_number_accepts_and_converts():
    assert jc.number(2, "$.n") == 2.0 and type(jc.number(2, "$.n")) is float
    assert jc.number(1, "$.n", low=0, high=1, low_open=True) == 1.0
    assert jc.number(0, "$.n", low=0) == 0.0
    assert jc.number(None, "$.n", nullable=True) is None


@pytest.mark.parametrize("value, kwargs, message", [
    ("3", {}, "'3' is not a number"),
    (True, {}, "true is not a number"),
    (None, {}, "null is not a number"),
    ([1], {}, "[1] is not a number"),
    ("x", {"low": 0, "low_open": True, "unit": "mm"}, "'x' is not a number > 0 mm"),
    ("x", {"low": 0, "high": 1, "low_open": True}, "'x' is not a number in (0, 1]"),
    ("x", {"high": 5}, "'x' is not a number <= 5"),
    (False, {"nullable": True}, "false is not a number or null"),
    (math.nan, {}, "NaN is not a finite number"),
    (-math.inf, {"low": 0}, "-Infinity is not a finite number"),
    (-3, {"low": 0, "low_open": True}, "-3 must be > 0"),
    (-3, {"low": 0, "unit": "mm"}, "-3 must be >= 0 mm"),
    (0, {"low": 0, "low_open": True}, "0 must be > 0"),
    (6, {"high": 5, "note": "the limit"}, "6 must be <= 5 (the limit)"),
    (5, {"high": 5, "high_open": True}, "5 must be < 5"),
    (1.4, {"low": 0, "high": 1, "low_open": True}, "1.4 is outside (0, 1]"),
    (0, {"low": 0, "high": 1, "low_open": True}, "0 is outside (0, 1]"),
    (60, {"low": 0, "high": 60.0, "low_open": True, "high_open": True, "unit": "mm",
          "note": "the patch diameter"}, "60 is outside (0, 60) mm (the patch diameter)"),
    (2, {"low": 5, "high": 360, "unit": "mm"}, "2 is outside [5, 360] mm"),
])
def test_number_errors_name_the_path(value, kwargs, message):
    e = error(jc.number, value, "$.a[0].n", **kwargs)
    assert (e.path, e.message) == ("$.a[0].n", message)


def test_integer():
    assert jc.integer(3, "$.i") == 3 and jc.integer(None, "$.i", nullable=True) is None
    for value, kwargs, message in [(2.0, {}, "2.0 is not an integer"),
                                   (True, {"low": 0, "nullable": True},
                                    "true is not an integer >= 0 or null"),
                                   (-1, {"low": 0}, "-1 must be >= 0"),
                                   (30, {"low": 0, "high": 20}, "30 is outside [0, 20]")]:
        e = error(jc.integer, value, "$.i", **kwargs)
        assert (e.path, e.message) == ("$.i", message)


def test_choice():
    assert jc.choice("up", "$.s", ("up", "down")) == "up"
    assert jc.choice("DOWN", "$.s", ("up", "down"), ignore_case=True) == "down"
    e = error(jc.choice, "DOWN", "$.s", ("up", "down"))
    assert (e.path, e.message) == ("$.s", "'DOWN' is not one of 'up', 'down'")
    e = error(jc.choice, 3, "$.s", ("up",))
    assert e.message == "3 is not one of 'up'"
    e = error(jc.choice, "xyz", "$.m[0].f", ["dst", "jef"], what="an export format")
    assert (e.path, e.message) == ("$.m[0].f", "'xyz' is not an export format (dst, jef)")


def test_unique():
    jc.unique(["a", "b", "A"], "$.p", "name")               # case counts unless ignored
    e = error(jc.unique, ["a", "b", "a"], "$.pieces", "name")
    assert (e.path, e.message) == ("$.pieces[2].name", "'a' is already the name of $.pieces[0]")
    e = error(jc.unique, ["SQ14b", "x", "sq14B"], "$.hoops", "name", ignore_case=True)
    assert (e.path, e.message) == ("$.hoops[2].name", "'sq14B' is already the name of "
                                   "$.hoops[0] ('SQ14b'; case is ignored)")
    e = error(jc.unique, ["p1", "p1"], "$.patches", "id")
    assert e.message == "'p1' is already the id of $.patches[0]"


@pytest.mark.parametrize("text, message", [
    ('{"a": ' + "7" * 5000 + "}", "$.a: 777"),
    ('{"a": [1, 1e999]}', "$.a[1]: 1e999 is too large (beyond the range of a float)"),
    ("[" * 100_000 + "]" * 100_000, "nested deeper than 32 levels"),
    ("[" * 40 + "]" * 40, "nested deeper than 32 levels"),
])
def test_loads_refuses_what_no_file_holds(text, message):
    """Over-long integers, floats beyond range and deep nesting are one short message each,
    never Python's ValueError or RecursionError."""
    with pytest.raises(InvalidInputError) as info:
        jc.loads(text, "f.json")
    assert message in str(info.value) and str(info.value).startswith("f.json: ")
    assert len(str(info.value)) < 200
    assert jc.loads("[" * 31 + "]" * 31, "f") is not None          # 32 levels are allowed


def test_number_beyond_the_float_range_and_long_values_are_shortened():
    e = error(jc.number, 10 ** 400, "$.x")
    assert e.message.endswith("... is too large") and len(e.message) < 80
    e = error(jc.obj, {"k" * 10_000: 1, "b": 2}, "$", ("a",))
    assert len(str(e)) < 300
    e = error(jc.obj, {f"x{i}": 1 for i in range(50)}, "$", ("a",))
    assert e.message.endswith("... (49 in all)")
    assert jc.show_all(["a", "b"]) == "a, b" and jc.clip("abcdef", 5) == "ab..."


def test_text_printable_refuses_control_characters():
    assert jc.text("p-1 é", "$.id", printable=True) == "p-1 é"
    for bad, code in (("p\x001", "U+0000 at character 2"), ("a\nb", "U+000A"), ("\x7f", "U+007F")):
        e = error(jc.text, bad, "$.id", printable=True)
        assert code in e.message and "control character" in e.message
    assert jc.text("a\nb", "$.notes") == "a\nb"                    # only where asked
