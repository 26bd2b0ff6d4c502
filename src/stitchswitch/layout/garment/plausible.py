"""Whether an imported piece has a plausible garment size: a pattern read with the wrong units
(inches taken as mm, or mm as inches) comes out 25.4 times too small or too large, which no
later step would notice. The bounds are generous: the longer side of a garment piece, from a
cuff or a pocket to a coat's front or a skirt panel, lies between ``MIN_SIDE_MM`` and
``MAX_SIDE_MM``."""
from __future__ import annotations

import numpy as np

__all__ = ["MIN_SIDE_MM", "MAX_SIDE_MM", "size_warning"]

MIN_SIDE_MM = 30.0
MAX_SIDE_MM = 2500.0


def size_warning(piece) -> str | None:
    """A sentence naming the piece and its size when it is implausible, else None."""
    w, h = (float(v) for v in np.ptp(np.asarray(piece.outline_mm, dtype=float), axis=0))
    longest = max(w, h)
    if MIN_SIDE_MM <= longest <= MAX_SIDE_MM:
        return None
    which = "small" if longest < MIN_SIDE_MM else "large"
    factor = 25.4 if longest < MIN_SIDE_MM else 1 / 25.4
    return (f"piece {piece.name} is {w:.1f} x {h:.1f} mm, implausibly {which} for a garment "
            f"piece (longest side outside {MIN_SIDE_MM:g}-{MAX_SIDE_MM:g} mm); if the file's "
            f"units are wrong, {factor:.4g} times this is {longest * factor:.0f} mm: give "
            "--units")
