"""Measured keypoints of fabricated patches: the CSV format and its validating loader.

One row per fabricated patch (format and rules in ``docs/data.md``). Required columns, in any
order: ``d_mm, fill, h_mm, r_a_mm, z_a_mm, r_b_mm, z_b_mm, split``; optional: ``sample_id``,
``force_N``, ``notes``; no other column is accepted. Lines whose first non-blank character is
``#`` are comments, blank lines are skipped, fields follow CSV quoting (a note may contain a
comma if quoted; a field may not span lines). The first comment ``# source: ...`` is the
file's provenance (``"unspecified"`` if there is none).

Every problem raises ``InvalidInputError`` naming the file, the line and the column: a missing,
unknown or repeated column; a wrong field count; a value that is empty, not a number, nan or
inf, or out of range (d in [10, 150] mm, fill in (0, 1], h, z_a, z_b in [0, 200) mm, r_a, r_b
in (0, 200) mm, force_N >= 0); a split other than ``train``/``val``; a sample id used twice
(both lines named); and an empty train or val split.
"""
from __future__ import annotations

import dataclasses
import hashlib
import os
from dataclasses import dataclass

import numpy as np

from stitchswitch.errors import InvalidInputError
from stitchswitch.files.shown import show
from stitchswitch.files.textio import csv_number, csv_records, read_text
from stitchswitch.reduced.model.params import DIAMETER_RANGE_MM

__all__ = ["Measurement", "MeasuredData", "QUANTITIES", "REQUIRED_COLUMNS", "OPTIONAL_COLUMNS",
           "SPLITS", "MAX_LENGTH_MM", "load_measurements", "parse_measurements"]

#: The five measurable quantities, in the order of ``MeasuredData.keypoints`` columns.
QUANTITIES = ("h", "r_a", "z_a", "r_b", "z_b")
REQUIRED_COLUMNS = ("d_mm", "fill", "h_mm", "r_a_mm", "z_a_mm", "r_b_mm", "z_b_mm", "split")
OPTIONAL_COLUMNS = ("sample_id", "force_N", "notes")
SPLITS = ("train", "val")
#: Upper bound (exclusive) of every measured length: larger values are taken as typos.
MAX_LENGTH_MM = 200.0


@dataclass(frozen=True)
class Measurement:
    """One fabricated patch: its design (d on the pre-stretched fabric, fill), its five
    measured keypoints (mm), its split, and where it came from (``line`` of the file).
    ``diameter_mm`` is the file's column ``d_mm``."""

    diameter_mm: float
    fill: float
    h_mm: float
    r_a_mm: float
    z_a_mm: float
    r_b_mm: float
    z_b_mm: float
    split: str
    sample_id: str = ""
    force_N: float | None = None
    notes: str = ""
    line: int = 0

    @property
    def label(self) -> str:
        """``sample_id`` if given, else ``line N``."""
        return self.sample_id or f"line {self.line}"


#: The ``Measurement`` field of each column whose name differs from it.
_FIELD_OF_COLUMN = {"d_mm": "diameter_mm"}


def _field_name(name: str) -> str:
    return f"{name}_mm" if name in QUANTITIES else name


@dataclass(frozen=True)
class MeasuredData:
    """Validated rows of a measured-data file, with its provenance line and the sha256 of its
    bytes (of the UTF-8 text for ``parse_measurements``)."""

    rows: tuple
    source: str
    sha256: str
    path: str

    @property
    def synthetic(self) -> bool:
        """True if the provenance line mentions the word 'synthetic'."""
        return "synthetic" in self.source.lower()

    def split(self, name: str) -> tuple:
        """The rows of split ``name`` (``train`` or ``val``), in file order."""
        if name not in SPLITS:
            raise InvalidInputError(f"split: {name!r} is not train or val")
        return tuple(r for r in self.rows if r.split == name)

    def array(self, field: str, split: str | None = None) -> np.ndarray:
        """One numeric column as a float array (all rows, or one split). ``field`` is a
        ``Measurement`` field (``diameter_mm``, ``h_mm``, ``force_N``...) or a quantity name of
        ``QUANTITIES`` (``"h"`` means ``h_mm``); a missing force is nan."""
        name = _field_name(field)
        numeric = {f.name for f in dataclasses.fields(Measurement)} - {"split", "sample_id", "notes"}
        if name not in numeric:
            raise InvalidInputError(f"field: {field!r} is not one of {', '.join(sorted(numeric))}")
        rows = self.rows if split is None else self.split(split)
        values = [getattr(r, name) for r in rows]
        return np.array([np.nan if v is None else v for v in values], dtype=float)

    def keypoints(self, split: str | None = None) -> np.ndarray:
        """(n, 5) measured keypoints in mm, columns h, r_a, z_a, r_b, z_b."""
        cols = [self.array(q, split) for q in QUANTITIES]
        return np.stack(cols, axis=1) if cols[0].size else np.zeros((0, len(QUANTITIES)))


def _check_range(value: float, where: str, column: str) -> None:
    lo, hi = DIAMETER_RANGE_MM
    if column == "d_mm":
        ok, rng = lo <= value <= hi, f"[{lo:g}, {hi:g}] mm"
    elif column == "fill":
        ok, rng = 0.0 < value <= 1.0, "(0, 1]"
    elif column in ("h_mm", "z_a_mm", "z_b_mm"):
        ok, rng = 0.0 <= value < MAX_LENGTH_MM, f"[0, {MAX_LENGTH_MM:g}) mm"
    else:  # r_a_mm, r_b_mm
        ok, rng = 0.0 < value < MAX_LENGTH_MM, f"(0, {MAX_LENGTH_MM:g}) mm"
    if not ok:
        raise InvalidInputError(f"{where}, column {column}: {value:g} is outside {rng}")


def _header(cells: list[str], where: str) -> list[str]:
    allowed = REQUIRED_COLUMNS + OPTIONAL_COLUMNS
    for k, c in enumerate(cells, start=1):
        if c not in allowed:
            raise InvalidInputError(
                f"{where}, column {k}: unknown column {show(c)} (required: {', '.join(REQUIRED_COLUMNS)}; "
                f"optional: {', '.join(OPTIONAL_COLUMNS)})")
        if c in cells[:k - 1]:
            raise InvalidInputError(f"{where}, column {k}: column {show(c)} appears twice in the header "
                                    f"(also column {cells.index(c) + 1})")
    missing = [c for c in REQUIRED_COLUMNS if c not in cells]
    if missing:
        raise InvalidInputError(f"{where}, column {missing[0]}: the header has no column "
                                f"{missing[0]!r} (need {', '.join(REQUIRED_COLUMNS)})")
    return cells


def _row(cells: list[str], header: list[str], where: str, lineno: int) -> Measurement:
    if len(cells) < len(header):
        k = len(cells)
        raise InvalidInputError(f"{where}, column {k + 1} ({header[k]}): missing; the row has "
                                f"{len(cells)} fields, the header has {len(header)}")
    if len(cells) > len(header):
        raise InvalidInputError(f"{where}, column {len(header) + 1}: beyond the header; the row "
                                f"has {len(cells)} fields, the header has {len(header)}")
    f = dict(zip(header, cells))
    values = {}
    for c in REQUIRED_COLUMNS[:-1]:
        value = csv_number(f[c], where, c)
        _check_range(value, where, c)
        values[_FIELD_OF_COLUMN.get(c, c)] = value
    if f["split"] not in SPLITS:
        raise InvalidInputError(f"{where}, column split: {show(f['split'])} is not train or val")
    force = None
    if f.get("force_N", "") != "":
        force = csv_number(f["force_N"], where, "force_N")
        if force < 0:
            raise InvalidInputError(f"{where}, column force_N: {force:g} is negative")
    return Measurement(**values, split=f["split"], sample_id=f.get("sample_id", ""),
                       force_N=force, notes=f.get("notes", ""), line=lineno)


def parse_measurements(text: str, name: str = "<text>") -> MeasuredData:
    """Validate measured data given as text; ``name`` labels the errors and becomes ``path``.
    ``sha256`` is that of the text encoded as UTF-8."""
    label = f"measured data {name}"
    rows, header, header_line, seen = [], None, 0, {}
    source, records = csv_records(text)
    for lineno, cells in records:
        where = f"{label}, line {lineno}"
        if header is None:
            header, header_line = _header(cells, where), lineno
            continue
        row = _row(cells, header, where, lineno)
        if row.sample_id:
            if row.sample_id in seen:
                raise InvalidInputError(f"{where}, column sample_id: {show(row.sample_id)} is also the "
                                        f"sample id on line {seen[row.sample_id]}")
            seen[row.sample_id] = lineno
        rows.append(row)
    if header is None:
        raise InvalidInputError(f"{label}: no header line (need {', '.join(REQUIRED_COLUMNS)})")
    for s in SPLITS:
        if not any(r.split == s for r in rows):
            raise InvalidInputError(f"{label}, line {header_line}, column split: the {s} split is "
                                    f"empty (no data row has split {s!r}; need train and val rows)")
    return MeasuredData(rows=tuple(rows), source=source or "unspecified",
                        sha256=hashlib.sha256(text.encode("utf-8")).hexdigest(), path=name)


def load_measurements(path: str | os.PathLike) -> MeasuredData:
    """Read and validate a measured-data file (UTF-8, an optional byte-order mark is dropped).
    ``sha256`` is that of the file's bytes, ``path`` the path as given."""
    path_s = os.fspath(path)
    name = repr(path_s)
    text = read_text(path, f"measured data {name}")
    try:
        with open(path, "rb") as f:
            raw = f.read()
    except OSError as exc:  # pragma: no cover - read_text just read it
        raise InvalidInputError(f"measured data {name}: cannot be read ({exc.strerror or exc})") from None
    if raw.decode("utf-8-sig", errors="replace") != text:
        raise InvalidInputError(f"measured data {name}: the file changed while it was being read")
    data = parse_measurements(text, name)
    return dataclasses.replace(data, sha256=hashlib.sha256(raw).hexdigest(), path=path_s)
