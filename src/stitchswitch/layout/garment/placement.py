"""Placing patches on a design's pieces: at a point, on a grid, or along a polyline.

All positions are garment coordinates (relaxed fabric, mm), like the piece outlines; the patch
diameter is the model's d on the pre-stretched fabric (docs/design-file.md). The functions only
compute centres and add patches; whether the patches fit their piece, keep their spacing and can
be sewn is the constraint check's business (``layout.check.constraints``).

New patch ids are ``<prefix><n>`` with n counting on from the largest n already used with that
prefix, so ids are unique and the same placement on the same design gives the same ids.
"""
from __future__ import annotations

import math
import re

import numpy as np

from stitchswitch.errors import InvalidInputError
from stitchswitch.layout.garment.design import CompositeSpec, Design, PatchSpec, Threads
from stitchswitch.layout.garment.design_io import validate_design

__all__ = ["piece_centroid", "grid_centres", "polyline_centres", "new_ids", "add_patches",
           "place_at", "place_grid", "place_along"]


def piece_centroid(outline_mm) -> tuple[float, float]:
    """Area centroid of a closed outline (garment mm)."""
    import shapely
    poly = shapely.make_valid(shapely.Polygon(np.asarray(outline_mm, dtype=float)))
    c = poly.centroid
    if c.is_empty or poly.area <= 0:
        raise InvalidInputError("the piece outline encloses no area: it has no centroid")
    return (float(c.x), float(c.y))


def _positive(name: str, value: float) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        raise InvalidInputError(f"{name}: {value!r} is not a finite number")
    if value <= 0:
        raise InvalidInputError(f"{name}: {value!r} must be > 0")
    return float(value)


def grid_centres(rows: int, cols: int, pitch_mm, centre_mm) -> np.ndarray:
    """(rows * cols, 2) centres of a rows x cols grid centred on ``centre_mm``; ``pitch_mm`` is
    one number or (along x, along y). Order: row by row from the top (largest y), each row left
    to right, like reading a button panel."""
    for name, v in (("rows", rows), ("cols", cols)):
        if isinstance(v, bool) or not isinstance(v, int) or v < 1:
            raise InvalidInputError(f"{name}: {v!r} must be a positive integer")
    px, py = (pitch_mm, pitch_mm) if np.isscalar(pitch_mm) else pitch_mm
    px, py = _positive("pitch_mm", px), _positive("pitch_mm", py)
    cx, cy = (float(v) for v in centre_mm)
    xs = cx + (np.arange(cols) - (cols - 1) / 2.0) * px
    ys = cy - (np.arange(rows) - (rows - 1) / 2.0) * py
    return np.array([(x, y) for y in ys for x in xs], dtype=float).reshape(-1, 2)


def polyline_centres(polyline_mm, pitch_mm: float) -> np.ndarray:
    """Centres at arc length 0, pitch, 2 pitch, ... along the polyline (its first point
    included, the last only if the length is a whole number of pitches, within 1e-6 mm)."""
    pitch = _positive("pitch_mm", pitch_mm)
    pts = np.asarray(polyline_mm, dtype=float)
    if pts.ndim != 2 or pts.shape[1] != 2 or len(pts) < 2:
        raise InvalidInputError("the polyline needs at least 2 points x,y")
    if not np.isfinite(pts).all():
        raise InvalidInputError("the polyline has a coordinate that is not a finite number")
    seg = np.hypot(*np.diff(pts, axis=0).T)
    cum = np.concatenate([[0.0], np.cumsum(seg)])
    total = cum[-1]
    if total <= 0:
        raise InvalidInputError("the polyline has zero length")
    s = np.arange(0, int(math.floor(total / pitch + 1e-6 / pitch)) + 1) * pitch
    s = np.minimum(s, total)
    return np.column_stack([np.interp(s, cum, pts[:, 0]), np.interp(s, cum, pts[:, 1])])


def new_ids(design: Design, count: int, prefix: str = "p") -> list[str]:
    """``count`` fresh ids ``<prefix><n>``, n continuing after the largest in use."""
    if not prefix or not prefix.strip():
        raise InvalidInputError("the id prefix must not be empty")
    pattern = re.compile(re.escape(prefix) + r"(\d+)$")
    used = {p.id for p in design.patches}
    nums = [int(m.group(1)) for pid in used if (m := pattern.match(pid))]
    start = max(nums, default=0) + 1
    ids = [f"{prefix}{start + k}" for k in range(count)]
    clash = [i for i in ids if i in used]
    if clash:
        raise InvalidInputError(f"patch id {clash[0]!r} is already used")
    return ids


def add_patches(design: Design, piece: str, centres_mm, diameter_mm: float, fill: float, *,
                id_prefix: str = "p", composite: CompositeSpec | None = None,
                outline_mm=None, conductive: str | None = None,
                threads: Threads = Threads(), state: str = "up") -> Design:
    """A copy of ``design`` with one patch per centre on ``piece`` (validated like a file)."""
    design.piece(piece)                                  # a clear error for an unknown piece
    _positive("diameter_mm", diameter_mm)
    if isinstance(fill, bool) or not isinstance(fill, (int, float)) or not 0 < fill <= 1:
        raise InvalidInputError(f"fill: {fill!r} is outside (0, 1]")
    centres = np.asarray(centres_mm, dtype=float).reshape(-1, 2)
    if not len(centres):
        raise InvalidInputError("no patch to place")
    ids = new_ids(design, len(centres), id_prefix)
    new = [PatchSpec(pid, piece, (float(x), float(y)), diameter_mm, fill, composite, outline_mm,
                     conductive, threads, state) for pid, (x, y) in zip(ids, centres)]
    start = len(design.patches)
    try:
        return validate_design(design.with_patches((*design.patches, *new)), "placement")
    except InvalidInputError as exc:
        # name the new patch by its id rather than by its index in the file-to-be
        msg = str(exc)
        for k, pid in enumerate(ids):
            msg = msg.replace(f"patches[{start + k}]", f"patch {pid}")
        raise InvalidInputError(msg) from None


def place_at(design: Design, piece: str, centre_mm, diameter_mm: float, fill: float,
             **kwargs) -> Design:
    """One patch at ``centre_mm``."""
    return add_patches(design, piece, [centre_mm], diameter_mm, fill, **kwargs)


def place_grid(design: Design, piece: str, rows: int, cols: int, pitch_mm, diameter_mm: float,
               fill: float, centre_mm=None, **kwargs) -> Design:
    """A rows x cols grid at ``pitch_mm``, centred on ``centre_mm`` (default: the piece's
    centroid)."""
    if centre_mm is None:
        centre_mm = piece_centroid(design.piece(piece).outline_mm)
    return add_patches(design, piece, grid_centres(rows, cols, pitch_mm, centre_mm),
                       diameter_mm, fill, **kwargs)


def place_along(design: Design, piece: str, polyline_mm, pitch_mm: float, diameter_mm: float,
                fill: float, **kwargs) -> Design:
    """Patches every ``pitch_mm`` along a polyline."""
    return add_patches(design, piece, polyline_centres(polyline_mm, pitch_mm), diameter_mm,
                       fill, **kwargs)
