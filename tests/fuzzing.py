"""Property-based fuzzing of the loaders (the ``tests/test_fuzz_*.py`` files).

Each test takes a real file (shipped data, ``tests/data/external``, or one written by the
package), corrupts it (``edited``: hypothesis draws the random generator of one of the
``fuzz_edits`` corruptions), and asserts the loader's contract on whatever comes out: it loads,
or it raises ``InvalidInputError`` with a message under ``MAX_MESSAGE`` characters (besides the
file's path) naming the file. Any other exception fails the test.

``FUZZ`` bounds every test to a few seconds and makes it deterministic (derandomize: CI runs
the same cases every time); ``STITCHSWITCH_FUZZ_EXAMPLES=2000`` runs more cases locally.
"""
from __future__ import annotations

import os

from hypothesis import HealthCheck, settings
from hypothesis import strategies as st

from stitchswitch.errors import InvalidInputError

MAX_MESSAGE = 300

FUZZ = settings(max_examples=int(os.environ.get("STITCHSWITCH_FUZZ_EXAMPLES", "60")),
                deadline=None, derandomize=True, database=None,
                suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large,
                                       HealthCheck.function_scoped_fixture])


def edited(seed: bytes, *edits):
    """The bytes of ``seed`` after one of ``edits`` (functions ``edit(rng, seed)``)."""
    return st.tuples(st.sampled_from(edits), st.randoms(use_true_random=False)).map(
        lambda pick: pick[0](pick[1], seed))


def check_refusal(load, path, name: str | None = None, data: bytes | None = None):
    """``load(path)`` (after writing ``data`` to ``path``, if given); if it raises, the error
    must be ``InvalidInputError`` with a short message (the file's path, the user's choice, not
    counted) that names the file (``name``, default the file name). Returns what loaded."""
    if data is not None:
        path.write_bytes(data)
    name = name or path.name
    try:
        return load(path)
    except InvalidInputError as exc:
        message = str(exc)
        short = message.replace(str(path), "<file>")
        assert len(short) < MAX_MESSAGE, f"{len(short)} characters: {short[:400]}"
        assert name in message, message
        return None
