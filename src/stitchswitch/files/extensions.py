"""Output paths checked by their extension before any work is done, with one clear error."""
from __future__ import annotations

import os

from stitchswitch.errors import InvalidInputError

__all__ = ["check_extension"]


def check_extension(path, allowed: tuple[str, ...], what: str = "output", hint: str = "") -> str:
    """The lower-case extension of ``path`` (``".png"``) if it is one of ``allowed``, else an
    ``InvalidInputError`` naming the path, its extension and the allowed ones (and ``hint``)."""
    path = os.fspath(path)
    ext = os.path.splitext(path)[1].lower()
    if ext not in allowed:
        raise InvalidInputError(f"{what} {path!r}: unknown extension {ext or '(none)'!r}; "
                                "use " + ", ".join(allowed) + (f" ({hint})" if hint else ""))
    return ext
