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
