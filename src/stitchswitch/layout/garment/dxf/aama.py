"""AAMA/ASTM pattern DXF (Gerber AccuMark, CLO): one BLOCK per piece and size, placed by an INSERT.

Layers (AAMA/ASTM D6673): 1 boundary (Gerber splits it into open POLYLINEs, chained here),
7 grain line, 8 internal lines, 4 notches. Texts in the block: `Piece Name: ...`, `SIZE: ...`;
in model space: `Units: ENGLISH|METRIC`. Keys are matched case-insensitively (CLO writes them
upper case).
"""
from __future__ import annotations

import numpy as np

from stitchswitch.errors import InvalidInputError
from stitchswitch.files.shown import clip
from stitchswitch.layout.garment.dxf.chain import chain_loops
from stitchswitch.layout.garment.dxf.generic import block_entities, check_point, flatten

UNIT_TEXT = {"ENGLISH": ("in", 25.4), "METRIC": ("mm", 1.0)}


def text_fields(entities) -> dict[str, str]:
    """`Key: value` TEXTs as {KEY: value} (key upper case)."""
    out = {}
    for e in entities:
        text = e.dxf.get("text") if e.dxftype() == "TEXT" else None
        if isinstance(text, str) and ":" in text:
            key, value = text.split(":", 1)
            out.setdefault(key.strip().upper(), value.strip())
    return out


def _block(doc, insert):
    """The block an INSERT places, None if it names none or a missing one."""
    name = insert.dxf.get("name")
    return doc.blocks.get(name) if isinstance(name, str) and name else None


def is_aama(doc) -> bool:
    """True when a block placed in model space carries a `Piece Name:` text."""
    return any("PIECE NAME" in text_fields(_block(doc, i) or [])
               for i in doc.modelspace().query("INSERT"))


def units_from_text(doc) -> tuple[str, float] | None:
    value = text_fields(doc.modelspace()).get("UNITS")
    if value is None:
        return None
    if value.upper() not in UNIT_TEXT:
        raise InvalidInputError(f"unknown units text 'Units: {clip(value)}' (expected ENGLISH or "
                                "METRIC)")
    return UNIT_TEXT[value.upper()]


def _polylines(entities, tolerance: float, limit: float, where: str) -> list:
    return [p for e in entities if (p := flatten(e, tolerance, limit, where)) is not None]


def read_aama(doc, tolerance: float, snap: float, unit: str, scale: float, source: str,
              limit: float):
    """(name, size, ring, annotations) per INSERT, in drawing units, INSERT transform applied."""
    pieces = []
    for insert in doc.modelspace().query("INSERT"):
        block = _block(doc, insert)
        if block is None:
            raise InvalidInputError(f"{source}: INSERT refers to a missing block "
                                    f"{clip(str(insert.dxf.get('name')))!r}")
        fields = text_fields(block)
        where = f"{source}: block {clip(block.name)!r}"
        layer = {}
        for e in block_entities(insert, where):
            layer.setdefault(e.dxf.get("layer"), []).append(e)
        fragments = _polylines(layer.get("1", []), tolerance, limit, where)
        if not fragments:
            raise InvalidInputError(f"{where}: no boundary on layer 1")
        rings = chain_loops(fragments, snap, where, unit, scale)
        if len(rings) != 1:
            raise InvalidInputError(f"{where}: boundary on layer 1 forms {len(rings)} closed "
                                    f"outlines, expected 1")
        lines = _polylines(layer.get("8", []), tolerance, limit, where)
        grain = _polylines(layer.get("7", []), tolerance, limit, where)
        notches = []
        for e in layer.get("4", []):
            if e.dxftype() in ("POINT", "LINE"):
                p = e.dxf.location if e.dxftype() == "POINT" else e.dxf.start  # a notch LINE starts on the edge
                check_point(p, limit, e, "notch", where)
                notches.append((p[0], p[1]))
        annotations = {"grain_line": grain[0] if grain else None,
                       "internal_lines": lines,
                       "notches": np.array(notches, dtype=float).reshape(-1, 2)}
        name = fields.get("PIECE NAME") or block.name
        pieces.append((name, fields.get("SIZE", ""), rings[0], annotations))
    return pieces
