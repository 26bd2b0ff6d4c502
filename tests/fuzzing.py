"""Property-based fuzzing of the loaders (the ``tests/test_fuzz_*.py`` files).

Each test takes a real file (shipped data, ``tests/data/external``, or one written by the
package), corrupts it with hypothesis, and asserts the loader's contract on whatever comes
out: it loads, or it raises ``InvalidInputError`` with a message under ``MAX_MESSAGE``
characters (besides the file's path) naming the file. Any other exception fails the test.

* ``byte_edits(seed)``: flips, insertions, deletions and a truncation of the bytes;
* ``line_edits(seed)``: lines deleted, repeated or replaced, and single cells or tokens
  replaced by ``NASTY`` values (text formats: CSV, DXF);
* ``json_edits(doc)``: one value anywhere in a JSON document replaced by a nasty one (wrong
  type, huge or long number, deep nesting, long or control-character string), a key removed or
  an unknown one added, written with the raw tokens (NaN, 1e999) JSON libraries refuse to write.

``FUZZ`` bounds every test to a few seconds and makes it deterministic (derandomize: CI runs
the same cases every time); ``STITCHSWITCH_FUZZ_EXAMPLES=2000`` runs more cases locally.
"""
from __future__ import annotations

import json
import os

from hypothesis import HealthCheck, settings
from hypothesis import strategies as st

from stitchswitch.errors import InvalidInputError

MAX_MESSAGE = 300

FUZZ = settings(max_examples=int(os.environ.get("STITCHSWITCH_FUZZ_EXAMPLES", "60")),
                deadline=None, derandomize=True, database=None,
                suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large,
                                       HealthCheck.function_scoped_fixture])

#: Values a field may be replaced with, as raw text.
NASTY = ["", "nan", "NaN", "inf", "-Infinity", "1e999", "-1e999", "-1", "0", "-0", "1e-320",
         "9" * 5000, "1" + "0" * 400, "x" * 140_000, "\x00", "null", "true", "[]", "{}", '"',
         ",", "#", "\ufeff", "é\u202e", "0x10", "1_000", " 7 ", "\t", "train", "val", "nan,nan"]


def check_refusal(load, path, name: str | None = None):
    """``load(path)``; if it raises, the error must be ``InvalidInputError`` with a short
    message (the file's path, the user's choice, not counted) that names the file (``name``,
    default the file name). Returns what loaded."""
    name = name or path.name
    try:
        return load(path)
    except InvalidInputError as exc:
        message = str(exc)
        short = message.replace(str(path), "<file>")
        assert len(short) < MAX_MESSAGE, f"{len(short)} characters: {short[:400]}"
        assert name in message, message
        return None


@st.composite
def byte_edits(draw, seed: bytes) -> bytes:
    data = bytearray(seed)
    for _ in range(draw(st.integers(1, 6))):
        op = draw(st.sampled_from(["flip", "insert", "delete", "truncate", "zero"]))
        at = draw(st.integers(0, max(len(data) - 1, 0)))
        if op == "flip" and data:
            data[at] ^= 1 << draw(st.integers(0, 7))
        elif op == "insert":
            data[at:at] = draw(st.binary(min_size=1, max_size=16))
        elif op == "delete":
            del data[at:at + draw(st.integers(1, 64))]
        elif op == "truncate":
            del data[at:]
        elif data:
            data[at:at + draw(st.integers(1, 32))] = bytes(min(32, len(data) - at))
    return bytes(data)


@st.composite
def line_edits(draw, seed: str, separator: str = ",") -> str:
    lines = seed.split("\n")
    for _ in range(draw(st.integers(1, 4))):
        op = draw(st.sampled_from(["delete", "repeat", "replace", "cell", "cell"]))
        i = draw(st.integers(0, len(lines) - 1))
        if op == "delete":
            del lines[i:i + draw(st.integers(1, 8))]
        elif op == "repeat":
            lines[i:i] = lines[i:i + draw(st.integers(1, 8))]
        elif op == "replace":
            lines[i] = draw(st.sampled_from(NASTY))
        else:
            cells = lines[i].split(separator)
            cells[draw(st.integers(0, len(cells) - 1))] = draw(st.sampled_from(NASTY))
            lines[i] = separator.join(cells)
        if not lines:
            lines = [""]
    return "\n".join(lines)


_RAW = "@@RAW@@"
#: Raw JSON replacements: tokens and structures no JSON writer produces.
RAW_JSON = ["NaN", "Infinity", "-Infinity", "1e999", "9" * 5000, "1" + "0" * 400, "-" + "9" * 320,
            "[" * 5000 + "]" * 5000, "[" * 40 + "1" + "]" * 40, '"' + "x" * 100_000 + '"',
            '"p\\u00001"', '"a\\nb"', "true", "null", "[]", "{}", '{"a": 1, "a": 2}', "0.5",
            "-3", "1e-400", '""', '"#zzzzzz"', "[0, 0]", "[[0, 0], [1, 0]]"]


def _paths(value, path=()):
    yield path
    if isinstance(value, dict):
        for k, v in value.items():
            yield from _paths(v, path + (k,))
    elif isinstance(value, list):
        for i, v in enumerate(value):
            yield from _paths(v, path + (i,))


def _replace(doc, path, new):
    if not path:
        return new
    target = doc
    for key in path[:-1]:
        target = target[key]
    target[path[-1]] = new
    return doc


@st.composite
def json_edits(draw, doc) -> str:
    doc = json.loads(json.dumps(doc))
    raws = []
    for _ in range(draw(st.integers(1, 3))):
        paths = list(_paths(doc))
        path = draw(st.sampled_from(paths))
        op = draw(st.sampled_from(["raw", "raw", "delete", "unknown"]))
        if op == "raw" or not path:
            raws.append(draw(st.sampled_from(RAW_JSON)))
            doc = _replace(doc, path, f"{_RAW}{len(raws) - 1}")
        else:
            parent = doc
            for key in path[:-1]:
                parent = parent[key]
            if op == "delete":
                del parent[path[-1]]
            elif isinstance(parent, dict):
                parent[draw(st.sampled_from(["x", "k" * 5000, "fil", "\x00"]))] = 1
        if not isinstance(doc, (dict, list)):
            break
    text = json.dumps(doc)
    for k, raw in enumerate(raws):
        text = text.replace(json.dumps(f"{_RAW}{k}"), raw)
    return text
