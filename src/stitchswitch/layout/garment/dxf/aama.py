"""AAMA/ASTM pattern DXF (Gerber AccuMark, CLO): one BLOCK per piece and size, placed by an INSERT.

Layers (AAMA/ASTM D6673): 1 boundary (Gerber splits it into open POLYLINEs, chained here),
7 grain line, 8 internal lines, 4 notches. Texts in the block: `Piece Name: ...`, `SIZE: ...`;
in model space: `Units: ENGLISH|METRIC`. Keys are matched case-insensitively (CLO writes them
upper case).
"""
from __future__ import annotations

import numpy as np

from stitchswitch.errors import InvalidInputError
from stitchswitch.layout.garment.dxf.generic import chain_loops, flatten

UNIT_TEXT = {"ENGLISH": ("in", 25.4), "METRIC": ("mm", 1.0)}


def text_fields(entities) -> dict[str, str]:
    """`Key: value` TEXTs as {KEY: value} (key upper case)."""
    out = {}
    for e in entities:
        if e.dxftype() == "TEXT" and ":" in e.dxf.text:
            key, value = e.dxf.text.split(":", 1)
            out.setdefault(key.strip().upper(), value.strip())
    return out


def is_aama(doc) -> bool:
    """True when a block placed in model space carries a `Piece Name:` text."""
    return any("PIECE NAME" in text_fields(doc.blocks.get(i.dxf.name) or [])
               for i in doc.modelspace().query("INSERT"))


def units_from_text(doc) -> tuple[str, float] | None:
    value = text_fields(doc.modelspace()).get("UNITS")
    if value is None:
        return None
    if value.upper() not in UNIT_TEXT:
        raise InvalidInputError(f"unknown units text 'Units: {value}' (expected ENGLISH or METRIC)")
    return UNIT_TEXT[value.upper()]


def read_aama(doc, tolerance: float, snap: float, unit: str, scale: float, source: str):
    """(name, size, ring, annotations) per INSERT, in drawing units, INSERT transform applied."""
    pieces = []
    for insert in doc.modelspace().query("INSERT"):
        block = doc.blocks.get(insert.dxf.name)
        if block is None:
            raise InvalidInputError(f"{source}: INSERT refers to a missing block '{insert.dxf.name}'")
        fields = text_fields(block)
        entities = list(insert.virtual_entities())
        layer = {}
        for e in entities:
            layer.setdefault(e.dxf.layer, []).append(e)
        where = f"{source}: block '{block.name}'"
        fragments = [p for e in layer.get("1", []) if (p := flatten(e, tolerance)) is not None]
        if not fragments:
            raise InvalidInputError(f"{where}: no boundary on layer 1")
        rings = chain_loops(fragments, snap, where, unit, scale)
        if len(rings) != 1:
            raise InvalidInputError(f"{where}: boundary on layer 1 forms {len(rings)} closed "
                                    f"outlines, expected 1")
        lines = [p for e in layer.get("8", []) if (p := flatten(e, tolerance)) is not None]
        grain = [p for e in layer.get("7", []) if (p := flatten(e, tolerance)) is not None]
        notches = [(e.dxf.location.x, e.dxf.location.y) if e.dxftype() == "POINT"
                   else (e.dxf.start.x, e.dxf.start.y)            # a notch LINE starts on the edge
                   for e in layer.get("4", []) if e.dxftype() in ("POINT", "LINE")]
        annotations = {"grain_line": grain[0] if grain else None,
                       "internal_lines": lines,
                       "notches": np.array(notches, dtype=float).reshape(-1, 2)}
        name = fields.get("PIECE NAME") or block.name
        pieces.append((name, fields.get("SIZE", ""), rings[0], annotations))
    return pieces
