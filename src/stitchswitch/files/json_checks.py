"""Checking the JSON files the package reads: one error per problem, naming the file and the
JSON path of the bad value.

Paths are JSONPath: ``$`` is the document, ``$.patches[2].diameter_mm`` a value in it (``child``
builds them). Every check takes the value and its path, returns the checked value and raises
``JsonError(path, message)`` when it is wrong; ``reporting(where)`` turns that into the package's
``InvalidInputError`` ``"<where>: <path>: <message>"``, e.g.
``design file 'd.json': $.patches[2].diameter_mm: -3 is outside [5, 360] mm``.

* ``loads(text, where)`` / ``load_file(path, where)``: parse, refusing what ``json.loads`` lets
  through silently: a duplicate key (it keeps the last) and NaN or Infinity (not JSON), and what
  no file of the package holds: nesting deeper than ``MAX_DEPTH`` levels, an integer of more
  than ``MAX_INT_DIGITS`` digits;
* ``obj`` (an object with its required and optional keys: unknown keys are refused, with a
  did-you-mean), ``array``, ``items`` (an array checked item by item), ``text``, ``number`` and
  ``integer`` (finite, with an optional range and unit), ``choice`` (one of a fixed set),
  ``unique`` (no two items of an array with the same name), ``fail`` (a check of the caller's
  own) and ``at(path)`` (an ``InvalidInputError`` of a value's own validation, placed at its
  path).

Values appear in messages as written in the file (``true``, ``null``, ``[1, 2]``) except
strings, which are quoted as in every other message of the package (``'abc'``), and never in
full: ``show`` shortens one to about 60 characters, ``show_all`` lists a few, ``clip`` shortens
any text (a long JSON path too); they live in ``files.shown`` and are re-exported here.
"""
from __future__ import annotations

import difflib
import json
import math
import unicodedata
from contextlib import contextmanager
from typing import NoReturn

from stitchswitch.errors import InvalidInputError
from stitchswitch.files.shown import clip, show, show_all

__all__ = ["ROOT", "MAX_DEPTH", "MAX_INT_DIGITS", "MAX_NAME", "JsonError", "child", "clip", "show",
           "show_all", "kind", "reporting", "at", "fail", "loads",
           "load_file", "obj", "array", "items", "text", "number", "integer", "choice", "unique"]

ROOT = "$"
_PATH_MAX = 60
_KEY_MAX = 32
#: Limits of a parsed document: no file the package reads nests more than a few levels or
#: holds an integer of more than a few digits.
MAX_DEPTH = 32
MAX_INT_DIGITS = 400
#: The longest name (a patch id, a piece name) ``text(..., printable=True)`` accepts.
MAX_NAME = 100


class JsonError(Exception):
    """A bad value at ``path``; ``reporting`` adds the file."""

    def __init__(self, path: str, message: str):
        self.path, self.message = path, message
        super().__init__(f"{clip(path, _PATH_MAX)}: {message}")


def child(path: str, key) -> str:
    """The path of item ``key`` (an array index or an object key, shortened to 32 characters)
    of the value at ``path``."""
    if isinstance(key, int) and not isinstance(key, bool):
        return f"{path}[{key}]"
    key = clip(str(key), _KEY_MAX)
    return f"{path}.{key}" if key.isidentifier() else f"{path}[{json.dumps(key)}]"


def kind(value) -> str:
    """The JSON type of ``value`` with its article: "an object", "null", ..."""
    if isinstance(value, bool):
        return "a boolean"
    if isinstance(value, (int, float)):
        return "a number"
    return {dict: "an object", list: "an array", str: "a string", type(None): "null"}.get(
        type(value), f"a {type(value).__name__}")


def _got(value) -> str:
    """'got a number (7)': the kind of a wrong value, and the value itself if it is short."""
    if value is None or isinstance(value, (dict, list)):
        return f"got {kind(value)}"
    return f"got {kind(value)} ({show(value)})"


@contextmanager
def reporting(where: str):
    """Raise a ``JsonError`` of the block as ``InvalidInputError("<where>: <path>: ...")``."""
    try:
        yield
    except JsonError as exc:
        raise InvalidInputError(f"{where}: {exc}") from None


@contextmanager
def at(path: str):
    """Raise an ``InvalidInputError`` of the block (a value's own validation) as a
    ``JsonError`` at ``path``."""
    try:
        yield
    except InvalidInputError as exc:
        raise JsonError(path, str(exc)) from None


def fail(path: str, message: str) -> NoReturn:
    raise JsonError(path, message)


# --- parsing -------------------------------------------------------------------------------

class _Duplicated(dict):
    """An object in which a key appeared more than once (found after parsing, with its path)."""

    duplicates: list


class _Refused:
    """A value the text spells but no loader can take, kept as a marker until its path is
    known: NaN, Infinity or -Infinity (Python's parser takes them, JSON has none) or an integer
    of more than ``MAX_INT_DIGITS`` digits (no field holds one; Python refuses to convert
    over 4,300)."""

    def __init__(self, message: str):
        self.message = message


def _constant(name: str) -> _Refused:
    return _Refused(f"{name} is not a finite number (JSON has no NaN or Infinity)")


def _integer(digits: str):
    n = len(digits.lstrip("-"))
    if n > MAX_INT_DIGITS:
        return _Refused(f"{clip(digits)} is too large (an integer of {n} digits)")
    return int(digits)


def _float(spelled: str):
    value = float(spelled)
    if not math.isfinite(value):
        return _Refused(f"{clip(spelled)} is too large (beyond the range of a float)")
    return value


def _pairs(pairs):
    out, duplicates = {}, []
    for key, value in pairs:
        if key in out:
            duplicates.append(key)
        out[key] = value
    if duplicates:
        out = _Duplicated(out)
        out.duplicates = duplicates
    return out


def _refuse_extensions(value, path: str) -> None:
    """Walk the parsed document (without recursion) for duplicates, refused values and
    nesting deeper than ``MAX_DEPTH``."""
    stack = [(value, path, 0)]
    while stack:
        value, path, depth = stack.pop()
        if isinstance(value, _Refused):
            fail(path, value.message)
        if isinstance(value, (dict, list)) and depth >= MAX_DEPTH:
            fail(path, f"nested deeper than {MAX_DEPTH} levels")
        if isinstance(value, dict):
            if isinstance(value, _Duplicated):
                fail(child(path, value.duplicates[0]), "duplicate key (a key may appear only "
                     "once in an object)")
            stack.extend((item, child(path, key), depth + 1)
                         for key, item in reversed(value.items()))
        elif isinstance(value, list):
            stack.extend((item, child(path, i), depth + 1)
                         for i, item in reversed(list(enumerate(value))))


def loads(text: str, where: str):
    """The parsed JSON ``text``; invalid JSON, a duplicate key or NaN/Infinity raise
    ``InvalidInputError`` starting with ``where`` (the duplicate and the constant by path)."""
    try:
        value = json.loads(text, object_pairs_hook=_pairs, parse_constant=_constant,
                           parse_int=_integer, parse_float=_float)
    except json.JSONDecodeError as exc:
        raise InvalidInputError(f"{where}: not valid JSON ({exc.msg} at line {exc.lineno}, "
                                f"column {exc.colno})") from None
    except RecursionError:
        raise InvalidInputError(f"{where}: not valid JSON (nested deeper than "
                                f"{MAX_DEPTH} levels)") from None
    with reporting(where):
        _refuse_extensions(value, ROOT)
    return value


def load_file(path, where: str, encoding: str = "utf-8-sig"):
    """``loads`` of the text of the file ``path`` (``files.textio.read_text``: an unreadable or
    non-UTF-8 file is an ``InvalidInputError`` starting with ``where`` too)."""
    from stitchswitch.files.textio import read_text

    return loads(read_text(path, where, encoding=encoding), where)


# --- containers ----------------------------------------------------------------------------

def obj(value, path: str, required=(), optional=(), *, what: str | None = None) -> dict:
    """``value``, an object whose keys are all in ``required`` or ``optional`` and which has
    every ``required`` key. ``what`` names the document in the error of a non-object (e.g.
    "a design": "$: a design must be a JSON object, got an array")."""
    if not isinstance(value, dict):
        head = f"{what} must be a JSON object" if what else "must be an object"
        fail(path, f"{head}, {_got(value)}")
    allowed = (*required, *optional)
    unknown = [k for k in value if k not in allowed]
    if unknown:
        message = "unknown key (allowed: " + ", ".join(allowed) + ")"
        absent = [k for k in allowed if k not in value]
        guess = difflib.get_close_matches(unknown[0][:100], absent, n=1, cutoff=0.75)
        if guess:
            message += f"; did you mean {guess[0]!r}?"
        if len(unknown) > 1:
            message += "; also unknown: " + show_all(unknown[1:], 2, quoted=True, width=24)
        fail(child(path, unknown[0]), message)
    missing = [k for k in required if k not in value]
    if missing:
        fail(child(path, missing[0]), "missing" + (" (also missing: " + ", ".join(
            map(repr, missing[1:])) + ")" if len(missing) > 1 else ""))
    return value


def array(value, path: str, *, nonempty: bool = False) -> list:
    """``value``, an array (with at least one item if ``nonempty``)."""
    head = "must be a non-empty array" if nonempty else "must be an array"
    if not isinstance(value, list):
        fail(path, f"{head}, {_got(value)}")
    if nonempty and not value:
        fail(path, f"{head}, got an empty one")
    return value


def items(value, path: str, check, *, nonempty: bool = False) -> list:
    """``[check(item, path_of_item) for each item]`` of the array ``value``."""
    return [check(item, child(path, i)) for i, item in enumerate(array(value, path,
                                                                       nonempty=nonempty))]


# --- scalars -------------------------------------------------------------------------------

def text(value, path: str, *, nonempty: bool = False, printable: bool = False) -> str:
    """``value``, a string (not blank if ``nonempty``; if ``printable``, a name that ends up in
    tables and messages: at most ``MAX_NAME`` characters, without control characters such as
    NUL or a line break)."""
    if not isinstance(value, str):
        fail(path, f"must be a string, {_got(value)}")
    if nonempty and not value.strip():
        fail(path, "must not be empty")
    if printable and len(value) > MAX_NAME:
        fail(path, f"{show(value)} is {len(value)} characters long, more than {MAX_NAME}")
    if printable:
        bad = next((i for i, c in enumerate(value) if unicodedata.category(c) == "Cc"), None)
        if bad is not None:
            fail(path, f"{show(value)} contains a control character (U+{ord(value[bad]):04X} "
                       f"at character {bad + 1})")
    return value


def _bound(x: float) -> str:
    return f"{x:g}"


def _range_text(low, high, low_open, high_open) -> str:
    return (("(" if low_open else "[") + _bound(low) + ", " + _bound(high)
            + (")" if high_open else "]"))


def _numeric(value, path, noun, low, high, low_open, high_open, unit, note, nullable):
    unit_text = f" {unit}" if unit else ""
    note_text = f" ({note})" if note else ""
    if low is not None and high is not None:
        wanted = f" in {_range_text(low, high, low_open, high_open)}{unit_text}"
    elif low is not None:
        wanted = f" {'>' if low_open else '>='} {_bound(low)}{unit_text}"
    elif high is not None:
        wanted = f" {'<' if high_open else '<='} {_bound(high)}{unit_text}"
    else:
        wanted = ""
    article = "an" if noun[0] in "aeiou" else "a"
    is_type = (isinstance(value, int) if noun == "integer" else isinstance(value, (int, float)))
    if isinstance(value, bool) or not is_type:
        fail(path, f"{show(value)} is not {article} {noun}{wanted}" + (" or null" if nullable
                                                                          else ""))
    try:
        finite = math.isfinite(value)
    except OverflowError:                       # an integer beyond the float range
        fail(path, f"{show(value)} is too large")
    if not finite:
        fail(path, f"{show(value)} is not a finite number")
    below = low is not None and (value <= low if low_open else value < low)
    above = high is not None and (value >= high if high_open else value > high)
    if below or above:
        if low is not None and high is not None:
            fail(path, f"{show(value)} is outside {_range_text(low, high, low_open, high_open)}"
                       f"{unit_text}{note_text}")
        fail(path, f"{show(value)} must be{wanted}{note_text}")
    return value


def number(value, path: str, *, low: float | None = None, high: float | None = None,
           low_open: bool = False, high_open: bool = False, unit: str = "", note: str = "",
           nullable: bool = False) -> float | None:
    """``value`` as a float: a finite number (not a boolean) in the range given by ``low`` and
    ``high`` (each included unless ``low_open`` / ``high_open``); ``unit`` and ``note`` are added
    to the message. With ``nullable``, null is allowed and returned as None."""
    if nullable and value is None:
        return None
    return float(_numeric(value, path, "number", low, high, low_open, high_open, unit, note,
                          nullable))


def integer(value, path: str, *, low: int | None = None, high: int | None = None,
            unit: str = "", note: str = "", nullable: bool = False) -> int | None:
    """``value``, an integer (not a boolean, not 2.0) in ``[low, high]``; null allowed (None) if
    ``nullable``."""
    if nullable and value is None:
        return None
    return int(_numeric(value, path, "integer", low, high, False, False, unit, note, nullable))


def choice(value, path: str, choices, *, what: str | None = None, ignore_case: bool = False):
    """The item of ``choices`` that ``value`` is (compared ignoring case if ``ignore_case``:
    the choice's own spelling is returned). The message lists the choices: "'x' is not one of
    'up', 'down'", or with ``what``: "'x' is not an export format (dst, jef)"."""
    choices = tuple(choices)
    for c in choices:
        if value == c or (ignore_case and isinstance(value, str) and isinstance(c, str)
                          and value.lower() == c.lower()):
            return c
    if what is None:
        fail(path, f"{show(value)} is not one of " + ", ".join(map(show, choices)))
    fail(path, f"{show(value)} is not {what} (" + (", ".join(map(str, choices)) or "none") + ")")


def unique(names, path: str, key: str, *, ignore_case: bool = False) -> None:
    """Refuse two items of the array at ``path`` whose ``key`` (``names``, in array order) is
    the same: "$.a[3].name: 'x' is already the name of $.a[1]"."""
    seen: dict = {}
    for i, name in enumerate(names):
        folded = name.lower() if ignore_case and isinstance(name, str) else name
        if folded in seen:
            first = seen[folded]
            same = "" if names[first] == name else f" ({show(names[first])}; case is ignored)"
            fail(child(child(path, i), key),
                 f"{show(name)} is already the {key} of {child(path, first)}{same}")
        seen[folded] = i
