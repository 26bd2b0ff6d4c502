"""Corruptions of real files for fuzzing the loaders, as plain functions of a
``random.Random``: the hypothesis tests (``fuzzing.py``, ``test_fuzz_*.py``) draw the generator,
``benchmarks/bench_fuzz.py`` seeds it, and both corrupt files the same way.

* ``byte_edit``: bit flips, inserted and deleted runs, zeroed runs, a truncation;
* ``line_edit``: lines deleted, repeated or replaced, and single cells (CSV) or values (DXF,
  one per line) replaced by ``NASTY`` ones;
* ``json_edit``: one to three values anywhere in a JSON document replaced by ``RAW_JSON`` text
  (wrong types, 5,000-digit or out-of-range numbers, NaN, deep nesting, long or
  control-character strings, a duplicate key), a key removed or an unknown one added;
* ``map_edit``: arrays of a design map removed or replaced by ``MAP_ARRAYS`` (wrong kind, shape
  or values).

No dependency beyond numpy, so that the benchmark runs without the test extra.
"""
from __future__ import annotations

import io
import json
import random

import numpy as np

#: Values a CSV cell or a DXF value may be replaced with.
NASTY = ["", "nan", "NaN", "inf", "-Infinity", "1e999", "-1e999", "-1", "0", "-0", "1e-320",
         "9" * 5000, "1" + "0" * 400, "x" * 140_000, "\x00", "null", "true", "[]", "{}", '"',
         ",", "#", "\ufeff", "\u202e", "0x10", "1_000", " 7 ", "\t", "train", "val", "nan,nan"]
#: Raw JSON text a value may be replaced with: tokens and structures no JSON writer produces.
RAW_JSON = ["NaN", "Infinity", "-Infinity", "1e999", "9" * 5000, "1" + "0" * 400, "-" + "9" * 320,
            "[" * 5000 + "]" * 5000, "[" * 40 + "1" + "]" * 40, '"' + "x" * 100_000 + '"',
            '"p\\u00001"', '"a\\nb"', "true", "null", "[]", "{}", '{"a": 1, "a": 2}', "0.5",
            "-3", "1e-400", '""', '"#zzzzzz"', "[0, 0]", "[[0, 0], [1, 0]]", "1e308", "-0.0"]
#: Keys an object may gain.
NEW_KEYS = ["x", "k" * 5000, "fil", "\x00"]
#: Arrays a map's array may be replaced with.
MAP_ARRAYS = [np.zeros(0), np.zeros((3, 3)), np.zeros((4, 3)), np.zeros((3, 4)),
              np.zeros((4, 3, 30), np.int32), np.full((4, 3), np.nan), np.array(np.inf),
              np.array("x"), np.array([42.0, 41.0, 40.0]), np.array([40.0, 40.0, 41.0, 42.0]),
              np.zeros((4, 3), bool), np.ones(4, np.int64) * 10 ** 6, np.array(1e-4),
              np.array(-1.0), np.full((4, 3), 7, np.int8), np.array(["a", "b"]),
              np.zeros((2, 2, 2)), np.zeros(3, np.int64)]


def byte_edit(rng: random.Random, seed: bytes) -> bytes:
    data = bytearray(seed)
    for _ in range(rng.randint(1, 6)):
        op = rng.choice(["flip", "flip", "insert", "delete", "truncate", "zero"])
        at = rng.randrange(max(len(data), 1))
        if op == "flip" and data:
            data[at] ^= 1 << rng.randrange(8)
        elif op == "insert":
            data[at:at] = bytes(rng.randrange(256) for _ in range(rng.randint(1, 16)))
        elif op == "delete":
            del data[at:at + rng.randint(1, 64)]
        elif op == "truncate":
            del data[at:]
        elif data:
            data[at:at + rng.randint(1, 32)] = bytes(min(32, len(data) - at))
    return bytes(data)


def line_edit(rng: random.Random, seed: bytes, separator: str = ",") -> bytes:
    lines = seed.decode("utf-8", errors="replace").split("\n")
    for _ in range(rng.randint(1, 4)):
        i = rng.randrange(len(lines))
        op = rng.choice(["delete", "repeat", "replace", "cell", "cell"])
        if op == "delete":
            del lines[i:i + rng.randint(1, 8)]
        elif op == "repeat":
            lines[i:i] = lines[i:i + rng.randint(1, 8)]
        elif op == "replace":
            lines[i] = rng.choice(NASTY)
        else:
            cells = lines[i].split(separator)
            cells[rng.randrange(len(cells))] = rng.choice(NASTY)
            lines[i] = separator.join(cells)
        lines = lines or [""]
    return "\n".join(lines).encode("utf-8", errors="surrogatepass")


def _paths(value, path=()):
    yield path
    if isinstance(value, dict):
        for k, v in value.items():
            yield from _paths(v, path + (k,))
    elif isinstance(value, list):
        for i, v in enumerate(value):
            yield from _paths(v, path + (i,))


def json_edit(rng: random.Random, seed: bytes) -> bytes:
    doc, raws = json.loads(seed), []
    for _ in range(rng.randint(1, 3)):
        path = rng.choice(list(_paths(doc)))
        op = rng.choice(["raw", "raw", "delete", "unknown"])
        if op == "raw" or not path:
            raws.append(rng.choice(RAW_JSON))
            marker = f"@@RAW{len(raws) - 1}@@"
            if not path:
                doc = marker
                break
        parent = doc
        for key in path[:-1]:
            parent = parent[key]
        if op == "raw":
            parent[path[-1]] = marker
        elif op == "delete":
            del parent[path[-1]]
        elif isinstance(parent, dict):
            parent[rng.choice(NEW_KEYS)] = 1
    text = json.dumps(doc)
    for k, raw in enumerate(raws):
        text = text.replace(json.dumps(f"@@RAW{k}@@"), raw)
    return text.encode("utf-8", errors="surrogatepass")


def map_edit(rng: random.Random, seed: bytes) -> bytes:
    with np.load(io.BytesIO(seed)) as f:
        arrays = {k: f[k] for k in f.files}
    for _ in range(rng.randint(1, 3)):
        name = rng.choice(sorted(arrays))
        k = rng.randrange(-1, len(MAP_ARRAYS))
        if k < 0:
            arrays.pop(name)
        else:
            arrays[name] = MAP_ARRAYS[k]
        if not arrays:
            break
    buf = io.BytesIO()
    np.savez_compressed(buf, **arrays)
    return buf.getvalue()
