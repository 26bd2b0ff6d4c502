"""Garment pattern pieces from DXF: `import_dxf(path) -> list[Piece]`, outlines in mm (docs/dxf.md).

Files are read with ezdxf's recover mode; what it repaired is logged as a warning and kept on
the returned list as `.repairs`. AAMA/ASTM pattern files (Gerber AccuMark, CLO) are read block by
block (``aama``); any other DXF contributes every closed contour in model space (``generic``).
"""
from __future__ import annotations

import logging
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from stitchswitch.errors import InvalidInputError
from stitchswitch.files import json_checks as jc
from stitchswitch.files.shown import clip
from stitchswitch.layout.garment.dxf.generic import GEOMETRY_ERRORS

log = logging.getLogger(__name__)

# $INSUNITS code -> (unit name, mm per unit)
INSUNITS = {1: ("in", 25.4), 2: ("ft", 304.8), 4: ("mm", 1.0), 5: ("cm", 10.0), 6: ("m", 1000.0)}
UNITS = {name: (name, mm) for name, mm in INSUNITS.values()}
#: The largest DXF file read, and the largest coordinate or radius accepted (1 km): a garment
#: pattern is a few MB and a few metres.
MAX_DXF_BYTES = 256 * 1024 ** 2
MAX_EXTENT_MM = 1e6


@dataclass(frozen=True, eq=False)
class Piece:
    """One pattern piece: closed outline (n, 2) in mm, last point not repeated."""
    name: str
    size: str
    outline_mm: np.ndarray
    source: str
    annotations: dict = field(default_factory=dict)   # grain_line, internal_lines, notches (mm)

    @property
    def bbox_mm(self) -> tuple[float, float]:
        """(width, height) of the outline's axis-aligned bounding box."""
        w, h = np.ptp(self.outline_mm, axis=0)
        return float(w), float(h)


class ImportedPieces(list):
    """The pieces of one file, plus `repairs`: the messages of ezdxf's recover mode."""

    def __init__(self, pieces, repairs: tuple[str, ...] = (), style: str = ""):
        super().__init__(pieces)
        self.repairs = repairs
        self.style = style          # "aama" or "generic"


def import_dxf(path, *, tolerance_mm: float = 0.1, snap_mm: float = 0.5,
               units: str | None = None) -> ImportedPieces:
    """Read the pattern pieces of a DXF file.

    tolerance_mm: maximum distance of the flattened outline from the true curve.
    snap_mm: open curves whose ends lie closer than this are joined; an outline closes the same way.
    units: "in", "ft", "mm", "cm" or "m" to override the file's units (needed when it has none).
    """
    from ezdxf import DXFError, recover

    from stitchswitch.layout.garment.dxf.aama import is_aama, read_aama, units_from_text
    from stitchswitch.layout.garment.dxf.generic import read_generic

    path = Path(path)
    if tolerance_mm <= 0 or snap_mm <= 0:
        raise InvalidInputError(f"tolerance_mm and snap_mm must be > 0, got {tolerance_mm}, {snap_mm}")
    try:
        size = path.stat().st_size
        with open(path, "rb") as f:
            f.seek(max(0, size - 64))
            truncated = b"EOF" not in f.read()          # recover mode would silently drop the rest
    except OSError as exc:
        raise InvalidInputError(f"{path}: not a readable DXF file ({exc.strerror or exc})") from None
    if size > MAX_DXF_BYTES:
        raise InvalidInputError(f"{path}: larger than {MAX_DXF_BYTES // 1024 ** 2} MiB, the limit "
                                "of a DXF input")
    if truncated:
        raise InvalidInputError(f"{path}: truncated DXF file: it does not end with the EOF marker")
    try:
        doc, auditor = recover.readfile(path)
    except Exception as exc:    # ezdxf's parser raises anything (IndexError, ...) on bad structure
        kind = "" if isinstance(exc, (DXFError, OSError)) else f"{type(exc).__name__}: "
        raise InvalidInputError(f"{path}: not a readable DXF file ({kind}"
                                f"{clip(str(exc), 100)})") from None
    repairs = tuple(f"{m.message}" for m in (*auditor.errors, *auditor.fixes))
    if repairs:
        log.warning("%s: ezdxf recover mode repaired %d problem(s), e.g. %s",
                    path, len(repairs), repairs[0])
    try:
        aama = is_aama(doc)
        unit, scale = _units(doc, units, units_from_text)
    except InvalidInputError as exc:
        raise InvalidInputError(f"{path}: {exc}") from None
    except GEOMETRY_ERRORS as exc:
        raise InvalidInputError(f"{path}: malformed DXF structure ({type(exc).__name__}: "
                                f"{clip(str(exc), 80)})") from None
    args = (tolerance_mm / scale, snap_mm / scale, unit, scale, str(path), MAX_EXTENT_MM / scale)
    raw = read_aama(doc, *args) if aama else read_generic(doc, *args)
    with jc.reporting(str(path)):
        for k, (name, size, _, _) in enumerate(raw, start=1):     # the design file's rules
            jc.text(name, f"piece {k} name", printable=True)
            jc.text(size, f"piece {k} size", printable=True)
    pieces = [Piece(name, size, ring * scale, str(path), _scaled(ann, scale))
              for name, size, ring, ann in raw]
    return ImportedPieces(pieces, repairs, "aama" if aama else "generic")


def _units(doc, override, units_from_text) -> tuple[str, float]:
    if override is not None:
        if override not in UNITS:
            raise InvalidInputError(f"unknown units '{override}' (expected one of {sorted(UNITS)})")
        return UNITS[override]
    code = doc.header.get("$INSUNITS", 0)
    if code in INSUNITS:
        return INSUNITS[code]
    found = units_from_text(doc)
    if found is not None:
        return found
    raise InvalidInputError(f"unknown units: $INSUNITS is {clip(str(code))} and there is no 'Units:' text; "
                            f"pass units= one of {sorted(UNITS)}")


def _scaled(ann: dict, scale: float) -> dict:
    out = {}
    for key, value in ann.items():
        if isinstance(value, list):
            out[key] = [np.asarray(v) * scale for v in value]
        else:
            out[key] = None if value is None else np.asarray(value) * scale
    return out
