"""Input values as error messages show them: shortened, so that a message stays one readable
line whatever the input holds (a 100 kB string, a list of a thousand names).

* ``show(value)``: a value as written in a JSON file (``true``, ``null``, ``[1, 2]``; strings
  quoted, ``'abc'``), at most about 60 characters;
* ``show_all(values)``: a few values of a list, then how many there are in all;
* ``clip(text)``: any text (a path, a cell) cut to a length, ending in "...".
"""
from __future__ import annotations

import json
import math

__all__ = ["clip", "show", "show_all"]

_SHOW_MAX = 60


def clip(text: str, most: int = 60) -> str:
    """``text`` shortened to ``most`` characters (ending in "..." when cut)."""
    return text if len(text) <= most else text[:most - 3] + "..."


def show_all(values, most: int = 5, *, quoted: bool = False, width: int = _SHOW_MAX) -> str:
    """``values`` as messages list them, at most ``most``, each shortened to ``width``
    characters: names unquoted, or ``show`` of each if ``quoted``."""
    values = list(values)
    out = ", ".join(clip(show(v) if quoted else str(v), width) for v in values[:most])
    return out + (f", ... ({len(values)} in all)" if len(values) > most else "")


def show(value) -> str:
    """``value`` as messages show it, shortened to about 60 characters."""
    if isinstance(value, str):
        out = repr(value)
    elif isinstance(value, float) and not math.isfinite(value):
        out = "NaN" if math.isnan(value) else ("Infinity" if value > 0 else "-Infinity")
    else:
        try:
            out = json.dumps(value, ensure_ascii=False)
        except (TypeError, ValueError):
            out = repr(value)
    return clip(out, _SHOW_MAX)
