"""Choosing the pieces of an imported pattern for a design: one size, some names.

Pattern files from pattern CAD hold every piece in every graded size (the Gerber tank: 2 pieces
x 14 sizes); a design holds the pieces of one size, each under a unique name.
"""
from __future__ import annotations

import math
import os

from stitchswitch.errors import InvalidInputError
from stitchswitch.layout.garment.design import PieceSpec

__all__ = ["select_pieces", "rectangle_piece"]


def _listing(values) -> str:
    return ", ".join(repr(v) for v in values) or "(none)"


def select_pieces(pieces, size: str | None = None, names=None, source: str | None = None
                  ) -> tuple[PieceSpec, ...]:
    """The design pieces of ``pieces`` (``dxf.reader.Piece``) of one size, optionally only those
    named in ``names`` (in file order). Several sizes and no ``size``, an unknown size or an
    unknown name raise ``InvalidInputError`` listing what the file has."""
    pieces = list(pieces)
    if not pieces:
        raise InvalidInputError("the pattern holds no piece")
    sizes = list(dict.fromkeys(p.size for p in pieces))
    if size is None:
        if len(sizes) > 1:
            raise InvalidInputError(f"the pattern has {len(sizes)} sizes; choose one with "
                                    f"--size: {_listing(sizes)}")
        size = sizes[0]
    elif size not in sizes:
        raise InvalidInputError(f"size {size!r} is not in the pattern; its sizes are "
                                f"{_listing(sizes)}")
    chosen = [p for p in pieces if p.size == size]
    if names:
        available = list(dict.fromkeys(p.name for p in chosen))
        unknown = [n for n in names if n not in available]
        if unknown:
            raise InvalidInputError(f"piece {unknown[0]!r} is not in size {size!r} of the "
                                    f"pattern; its pieces are {_listing(available)}")
        chosen = [p for p in chosen if p.name in set(names)]
    out, seen = [], {}
    for p in chosen:                      # a name used twice gets " #2", " #3", ...
        seen[p.name] = seen.get(p.name, 0) + 1
        name = p.name if seen[p.name] == 1 else f"{p.name} #{seen[p.name]}"
        out.append(PieceSpec(name, p.size, source if source is not None
                             else os.path.basename(p.source), p.outline_mm))
    return tuple(out)


def rectangle_piece(width_mm: float, height_mm: float, name: str = "rectangle") -> PieceSpec:
    """A width x height rectangle with its lower-left corner at the origin."""
    for label, v in (("width", width_mm), ("height", height_mm)):
        if not math.isfinite(v) or v <= 0:
            raise InvalidInputError(f"rectangle {label} {v:g} mm must be a positive number")
    if not name or not name.strip():
        raise InvalidInputError("the piece name must not be empty")
    return PieceSpec(name, "", f"rectangle {width_mm:g}x{height_mm:g}",
                     [[0.0, 0.0], [width_mm, 0.0], [width_mm, height_mm], [0.0, height_mm]])
