"""Machine embroidery export behind one format registry (meshio's registry is the model).

Every format is written by pyembroidery from a stitch plan converted to its 0.1 mm units (y
down, as pyembroidery expects). Before that, each move longer than the format's limit is
subdivided: a long stitch into stitches, a long jump into jumps, each at most the limit minus two
units long (the margin absorbs the rounding of both ends to 0.1 mm), so nothing is truncated by the writer. The
limits are pyembroidery 1.5.1's own writer constants (``MAX_STITCH_DISTANCE``, 0.1 mm per axis):

=====  ==========  =====================================================
DST    12.1 mm     +-121 units per record (balanced ternary, 3 bytes)
EXP    12.7 mm     signed byte per axis
JEF    12.7 mm     signed byte per axis
PES    204.7 mm    PEC long form, 12-bit signed per axis
VP3    25.5 mm     pyembroidery's limit (byte form +-127, long form 16-bit)
=====  ==========  =====================================================

JEF: trims are written (pyembroidery's ``trims=True``: three zero jumps, the Janome trim), the
header date is fixed so identical input gives identical bytes, and the hoop code is that of the
hoop passed in (``hoop_spec`` explains the codes). Every file ends with the format's END record.

Headers are rewritten from the real stitch bounds relative to the hoop centre (the origin of
the plan and of the files): pyembroidery writes JEF extents as half the design's size about the
centre and DST extents from its y-down bounds (so +Y and -Y swapped, and ``abs`` of an edge on
the far side). Here each field is the signed distance of the design's edge from the centre in
its direction (JEF left, top, right, bottom; DST +X, -X, +Y, -Y; negative: the design does not
reach that side), computed from the STITCH records as written (0.1 mm). The design label (DST
``LA``, PES name) is the ``label`` passed in (ASCII, 16 characters), not "Untitled".

EXP and VP3 are marked experimental (``EXPERIMENTAL``): pyembroidery's VP3 writer stores the move
after a trim as a stitch and EXP trim records decode differently in different readers, and no
independent decoder in the tests checks them (docs/embroidery.md).
"""
from __future__ import annotations

import io
import logging
import math
import pathlib
import re
import struct
from dataclasses import dataclass
from typing import Callable

import numpy as np

from stitchswitch.errors import InvalidInputError
from stitchswitch.files.atomic import atomic_write_bytes
from stitchswitch.layout.embroidery import stitches as st
from stitchswitch.layout.embroidery.hoop_spec import Hoop, jef_code_for
from stitchswitch.layout.embroidery.planar import length

log = logging.getLogger(__name__)

JEF_FIXED_DATE = "20000101000000"
#: formats whose trims no independent decoder confirms (``--help`` says so)
EXPERIMENTAL = ("exp", "vp3")


@dataclass(frozen=True)
class Format:
    name: str
    extensions: tuple[str, ...]
    writer: Callable[[object, io.BytesIO, Hoop | None], None]
    max_move_mm: float


FORMATS: dict[str, Format] = {}


def register_format(name: str, extensions, writer, max_move_mm: float) -> None:
    """Register a writer ``writer(pattern, stream, hoop)`` for ``name`` and its extensions."""
    FORMATS[name.lower()] = Format(name.lower(), tuple(e.lower() for e in extensions), writer,
                                   float(max_move_mm))


def supported_formats() -> list[str]:
    return sorted(FORMATS)


def get_format(name: str) -> Format:
    fmt = FORMATS.get(str(name).lower().lstrip("."))
    if fmt is None:
        raise InvalidInputError(f"unsupported embroidery format {name!r}; supported: "
                                + ", ".join(supported_formats()))
    return fmt


def format_from_path(path) -> Format:
    ext = pathlib.Path(path).suffix.lower()
    for fmt in FORMATS.values():
        if ext in fmt.extensions:
            return fmt
    raise InvalidInputError(f"unknown embroidery file extension {ext!r} of {str(path)!r}; "
                            "supported: " + ", ".join(supported_formats()))


# --- conversion ----------------------------------------------------------------------------

def subdivide(plan: st.StitchPlan, max_move_mm: float) -> st.StitchPlan:
    """The plan with every STITCH/JUMP move split into equal parts of at most
    ``max_move_mm - 0.2`` mm (so that the moves stay within the limit after rounding both ends
    to 0.1 mm)."""
    limit = max_move_mm - 0.2
    xy, cmd = [plan.xy_mm[0]], [plan.commands[0]]
    for k in range(1, len(plan.commands)):
        a, b, c = plan.xy_mm[k - 1], plan.xy_mm[k], plan.commands[k]
        if c in (st.STITCH, st.JUMP):
            n = max(1, int(math.ceil(length(b - a) / limit - 1e-12)))
            for i in range(1, n):
                xy.append(a + (b - a) * i / n)
                cmd.append(c)
        xy.append(b)
        cmd.append(c)
    return st.StitchPlan(np.asarray(xy), np.asarray(cmd, dtype=np.int8), plan.threads,
                         plan.stitches_per_minute)


def label_text(label: str | None) -> str:
    """The design label as the headers hold it: printable ASCII, at most 16 characters."""
    text = "".join(c if 32 <= ord(c) < 127 and c != ":" else "_"
                   for c in str(label or "stitchswitch"))
    return text[:16] or "stitchswitch"


def to_pattern(plan: st.StitchPlan, label: str | None = None):
    """A pyembroidery ``EmbPattern`` (0.1 mm, y down) with the plan's records and threads."""
    import pyembroidery as pe
    pattern = pe.EmbPattern()
    pattern.metadata("name", label_text(label))
    for t in plan.threads:
        thread = pe.EmbThread()
        thread.set_color(*t.rgb)
        thread.description = t.name
        pattern.add_thread(thread)
    codes = {st.STITCH: pe.STITCH, st.JUMP: pe.JUMP, st.TRIM: pe.TRIM,
             st.COLOR_CHANGE: pe.COLOR_CHANGE, st.END: pe.END}
    for (x, y), c in zip(plan.xy_mm.tolist(), plan.commands.tolist()):
        pattern.add_stitch_absolute(codes[c], round(x * 10.0), round(-y * 10.0))
    return pattern


def encode(plan: st.StitchPlan, fmt: str, hoop: Hoop | None = None,
           label: str | None = None) -> bytes:
    """The file bytes of ``plan`` in format ``fmt`` (deterministic). ``hoop`` is the hoop the
    plan is stitched in (the caller chooses it, e.g. ``Machine.choose_hoop``); it gives the JEF
    header's hoop code (``hoop_spec.jef_code_for``). ``label``: the design name in the header."""
    f = get_format(fmt)
    pattern = to_pattern(subdivide(plan, f.max_move_mm), label)
    buf = io.BytesIO()
    f.writer(pattern, buf, hoop)
    return buf.getvalue()


def write(path, plan: st.StitchPlan, fmt: str | None = None, hoop: Hoop | None = None,
          label: str | None = None) -> None:
    """Write ``plan`` to ``path`` atomically (format from ``fmt`` or the extension)."""
    name = get_format(fmt).name if fmt else format_from_path(path).name
    atomic_write_bytes(path, encode(plan, name, hoop, label))


def stitch_bounds(pattern) -> tuple[int, int, int, int]:
    """(xmin, ymin, xmax, ymax) of the pattern's STITCH records, 0.1 mm, **y up**."""
    import pyembroidery as pe
    pts = [(s[0], s[1]) for s in pattern.stitches if s[2] & pe.COMMAND_MASK == pe.STITCH]
    if not pts:
        return 0, 0, 0, 0
    xs = [int(round(x)) for x, _ in pts]
    ys = [-int(round(y)) for _, y in pts]
    return min(xs), min(ys), max(xs), max(ys)


# --- the writers -----------------------------------------------------------------------

def _pe_writer(method: str, settings: dict | None = None):
    def writer(pattern, stream, hoop):
        import pyembroidery as pe
        getattr(pe, method)(pattern, stream, dict(settings or {}))
    return writer


def _write_jef(pattern, stream, hoop):
    import pyembroidery as pe
    tmp = io.BytesIO()
    pe.write_jef(pattern, tmp, {"trims": True, "date": JEF_FIXED_DATE})
    data = bytearray(tmp.getvalue())
    x0, y0, x1, y1 = stitch_bounds(pattern)
    left, top, right, bottom = -x0, y1, x1, -y0
    struct.pack_into("<4i", data, 36, left, top, right, bottom)
    # distances from the edges of the 110x110, 50x50, 140x200 and custom (140x200) fields
    for k, (w, h) in enumerate(((1100, 1100), (500, 500), (1400, 2000), (1400, 2000))):
        edges = (w // 2 - left, h // 2 - top, w // 2 - right, h // 2 - bottom)
        struct.pack_into("<4i", data, 52 + 16 * k, *(edges if min(edges) >= 0 else (-1,) * 4))
    if hoop is not None:
        code, published = jef_code_for(hoop, (x0 / 10, y0 / 10, x1 / 10, y1 / 10))
        if not published:
            log.warning("no published JEF hoop code for %s; wrote %d, the smallest coded field "
                        "holding the design about the centre", hoop, code)
        struct.pack_into("<i", data, 32, code)
    stream.write(bytes(data))


_DST_FIELD = re.compile(rb"([+-][XY]):[ +-]?\s*-?\d+\r")


def _write_dst(pattern, stream, hoop):
    import pyembroidery as pe
    tmp = io.BytesIO()
    pe.write_dst(pattern, tmp, {})
    data = bytearray(tmp.getvalue())
    x0, y0, x1, y1 = stitch_bounds(pattern)
    values = {b"+X": x1, b"-X": -x0, b"+Y": y1, b"-Y": -y0}
    head = bytes(data[:512])
    head = _DST_FIELD.sub(lambda m: m.group(1) + b":" + b"%5d" % values[m.group(1)] + b"\r", head)
    data[:512] = head[:512].ljust(512, b" ")
    stream.write(bytes(data))


def _limit(module: str) -> float:
    import importlib
    return importlib.import_module(f"pyembroidery.{module}").MAX_STITCH_DISTANCE / 10.0


register_format("jef", [".jef"], _write_jef, _limit("JefWriter"))
register_format("dst", [".dst"], _write_dst, _limit("DstWriter"))
register_format("pes", [".pes"], _pe_writer("write_pes"), _limit("PesWriter"))
register_format("exp", [".exp"], _pe_writer("write_exp"), _limit("ExpWriter"))
register_format("vp3", [".vp3"], _pe_writer("write_vp3"), _limit("Vp3Writer"))
