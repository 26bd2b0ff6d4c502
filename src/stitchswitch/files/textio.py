"""Reading user-supplied text files with one clear error per problem."""
from __future__ import annotations

import os

from stitchswitch.errors import InvalidInputError


def read_text(path: str | os.PathLike, where: str, encoding: str = "utf-8-sig") -> str:
    """The file's text; an unreadable or non-UTF-8 file raises ``InvalidInputError``
    starting with ``where`` (e.g. "material file 'm.json'"). A UTF-8 byte-order mark is
    dropped."""
    try:
        with open(path, "rb") as f:
            return f.read().decode(encoding)
    except OSError as exc:
        raise InvalidInputError(f"{where}: cannot be read ({exc.strerror or exc})") from None
    except UnicodeDecodeError as exc:
        raise InvalidInputError(f"{where}: is not UTF-8 text ({exc.reason} at byte {exc.start})") from None


def csv_records(text: str):
    """(source, records) of a CSV text with ``#`` comment lines: ``source`` is the text after
    the first ``# source:`` comment (None if there is none) and ``records`` the list of
    (line number, stripped cells) of the other non-blank lines, header included."""
    import csv

    source, records = None, []
    for lineno, line in enumerate(text.splitlines(), start=1):
        stripped = line.strip()
        if stripped.startswith("#"):
            if source is None and stripped.startswith("# source:"):
                source = stripped[len("# source:"):].strip()
            continue
        if stripped:
            records.append((lineno, [c.strip() for c in next(csv.reader([line]))]))
    return source, records


def csv_number(text: str, where: str, column: str) -> float:
    """A finite float from a CSV cell; errors name ``where`` (file and line) and the column."""
    import math

    if text == "":
        raise InvalidInputError(f"{where}, column {column}: the value is empty")
    try:
        value = float(text)
    except ValueError:
        raise InvalidInputError(f"{where}, column {column}: {text!r} is not a number") from None
    if not math.isfinite(value):
        raise InvalidInputError(f"{where}, column {column}: {text!r} is not a finite number")
    return value
