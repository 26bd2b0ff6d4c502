"""``json_safe``: a value made ready for strict JSON (``json.dumps(..., allow_nan=False)``).

Dicts and sequences are converted element by element (tuples become lists), numpy scalars
become Python scalars and non-finite floats (nan, inf) become ``None`` (JSON ``null``), so a
missing number reads as missing rather than breaking the file.
"""
from __future__ import annotations

import math

import numpy as np

__all__ = ["json_safe"]


def json_safe(obj):
    """``obj`` with numpy scalars as Python scalars and nan/inf as ``None``, recursively."""
    if isinstance(obj, dict):
        return {k: json_safe(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [json_safe(v) for v in obj]
    if isinstance(obj, np.generic):
        obj = obj.item()
    if isinstance(obj, float) and not math.isfinite(obj):
        return None
    return obj
