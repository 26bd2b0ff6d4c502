"""Reading user-supplied text files with one clear error per problem.

Text inputs (material, design, machine catalogue, measured and force CSV) are read whole, so
their size is bounded: a file over ``MAX_TEXT_BYTES`` (16 MiB, far above any real input) is
refused after reading at most that much, so that a path such as ``/dev/zero`` cannot exhaust
memory.
"""
from __future__ import annotations

import os

from stitchswitch.errors import InvalidInputError

#: The largest text input read, in bytes.
MAX_TEXT_BYTES = 16 * 1024 * 1024


def read_text(path: str | os.PathLike, where: str, encoding: str = "utf-8-sig") -> str:
    """The file's text; an unreadable, non-UTF-8 or over-``MAX_TEXT_BYTES`` file raises
    ``InvalidInputError`` starting with ``where`` (e.g. "material file 'm.json'"). A UTF-8
    byte-order mark is dropped."""
    try:
        with open(path, "rb") as f:
            raw = f.read(MAX_TEXT_BYTES + 1)
    except OSError as exc:
        raise InvalidInputError(f"{where}: cannot be read ({exc.strerror or exc})") from None
    if len(raw) > MAX_TEXT_BYTES:
        raise InvalidInputError(f"{where}: larger than {MAX_TEXT_BYTES // (1024 * 1024)} MiB, "
                                "the limit of a text input")
    try:
        return raw.decode(encoding)
    except UnicodeDecodeError as exc:
        raise InvalidInputError(f"{where}: is not UTF-8 text ({exc.reason} at byte {exc.start})") from None


def csv_records(text: str):
    """(source, records) of a CSV text with ``#`` comment lines: ``source`` is the text after
    the first ``# source:`` comment (None if there is none) and ``records`` the list of
    (line number, stripped cells) of the other non-blank lines, header included. A field may
    be as long as its line (the csv module's own 128 KiB field limit does not apply: the
    text's size is bounded by ``read_text``)."""
    import csv

    source, records = None, []
    limit = csv.field_size_limit()
    try:
        for lineno, line in enumerate(text.splitlines(), start=1):
            stripped = line.strip()
            if stripped.startswith("#"):
                if source is None and stripped.startswith("# source:"):
                    source = stripped[len("# source:"):].strip()
                continue
            if stripped:
                csv.field_size_limit(max(limit, len(line) + 1))
                records.append((lineno, [c.strip() for c in next(csv.reader([line]))]))
    finally:
        csv.field_size_limit(limit)
    return source, records


def csv_number(text: str, where: str, column: str) -> float:
    """A finite float from a CSV cell; errors name ``where`` (file and line) and the column,
    and show the cell shortened (``files.shown.show``)."""
    import math

    from stitchswitch.files.shown import show

    if text == "":
        raise InvalidInputError(f"{where}, column {column}: the value is empty")
    try:
        value = float(text)
    except ValueError:
        raise InvalidInputError(f"{where}, column {column}: {show(text)} is not a number") from None
    if not math.isfinite(value):
        raise InvalidInputError(f"{where}, column {column}: {show(text)} is not a finite number")
    return value
