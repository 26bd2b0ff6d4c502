"""What an embroidery file from anywhere holds: stitch, jump, trim and colour counts, where its
stitches lie, and the hoops of a machine that hold them there (``stitchswitch inspect``).

Machine files keep their coordinates about the hoop centre, and the moves that start and end a
design (from the centre to the first stitch, between blocks, back at the end) are jumps, not
stitches: the extents reported are those of the stitch points alone (``stitch_bounds_mm``:
xmin, ymin, xmax, ymax about the hoop centre, y away from the operator, i.e. pyembroidery's
y-down axis turned up), and ``span_bounds_mm`` is the same over every point, moves included.
A hoop *holds* the file when every stitch lies in its field where it is (|x| <= W/2 and
|y| <= H/2 about the centre; the field's margin is not applied), so an off-centre design needs
a larger hoop than its size alone suggests; ``centred_fit`` lists the hoops that would hold it
moved to the centre. A JEF file's header names a hoop (an integer code at byte 32,
``hoop_spec.JEF_HOOP_CODES``); it is reported with the field the code stands for, the
machine's hoops that carry that code, and whether the stitches lie inside that field.

The file is read with pyembroidery, whose readers take any bytes and may raise anything on a
malformed file or return an empty pattern; this module turns all of that into one
``InvalidInputError`` naming the file, without pyembroidery's internal messages: a file over
``MAX_EMBROIDERY_BYTES``, an extension no reader handles, a header shorter than its format's
(DST: 512 bytes) or without its signature (PES: ``#PES``), a reader failure, and a pattern
without a single stitch, with all its stitches at one point or with non-finite coordinates are
all refused.
"""
from __future__ import annotations

import contextlib
import io
import math
import pathlib

from stitchswitch.errors import InvalidInputError
from stitchswitch.files.shown import clip
from stitchswitch.layout.embroidery.hoop_spec import JEF_HOOP_CODES

#: byte offset of the JEF header's hoop code (int32, little endian)
_JEF_HOOP_OFFSET = 32

__all__ = ["MAX_EMBROIDERY_BYTES", "summarise", "jef_header_hoop"]

#: The largest embroidery file read (machine files are at most a few MB).
MAX_EMBROIDERY_BYTES = 64 * 1024 ** 2
#: Per extension: (smallest size in bytes, signature at the start).
_HEADERS = {"dst": (512, b""), "pes": (8, b"#PES")}


def _reader_extensions() -> list[str]:
    import pyembroidery as pe

    return sorted(f["extension"] for f in pe.supported_formats() if f.get("reader"))


def _check_header(path: pathlib.Path, ext: str, where: str) -> None:
    size = path.stat().st_size
    if size > MAX_EMBROIDERY_BYTES:
        raise InvalidInputError(f"{where}: larger than {MAX_EMBROIDERY_BYTES // 1024 ** 2} MiB, "
                                "the limit of an embroidery file")
    smallest, signature = _HEADERS.get(ext, (1, b""))
    if size < smallest:
        raise InvalidInputError(f"{where}: {size} bytes, too short for a {ext.upper()} file "
                                f"(at least {smallest})")
    with open(path, "rb") as f:
        start = f.read(len(signature))
    if start != signature:
        raise InvalidInputError(f"{where}: not a {ext.upper()} file (it does not start with "
                                f"{signature.decode()})")


def _read(path: pathlib.Path, ext: str, where: str):
    import pyembroidery as pe

    settings = {"trims": True} if ext == "jef" else None
    try:
        with contextlib.redirect_stdout(io.StringIO()):          # some readers print
            pattern = pe.read(str(path), settings)
    except Exception:   # pyembroidery's readers raise anything on malformed input
        pattern = None
    if pattern is None:
        raise InvalidInputError(f"{where}: not a readable {ext.upper()} file (malformed data)")
    return pattern


def jef_header_hoop(path) -> int | None:
    """The hoop code in a JEF file's header (None if the file is too short to have one)."""
    with open(path, "rb") as f:
        head = f.read(_JEF_HOOP_OFFSET + 4)
    if len(head) < _JEF_HOOP_OFFSET + 4:
        return None
    return int.from_bytes(head[_JEF_HOOP_OFFSET:], "little", signed=True)


def _holds(field_mm, bounds_mm) -> bool:
    """Whether every point of ``bounds_mm`` (about the centre) lies in the field centred."""
    w, h = field_mm
    x0, y0, x1, y1 = bounds_mm
    return max(-x0, x1) <= w / 2 + 1e-9 and max(-y0, y1) <= h / 2 + 1e-9


def _hoop_report(machine, bounds_mm, ext: str, path: pathlib.Path) -> dict:
    w, h = bounds_mm[2] - bounds_mm[0], bounds_mm[3] - bounds_mm[1]
    out = {"machine": machine.name,
           "hoops": [str(hp) for hp in machine.hoops
                     if _holds((hp.width_mm, hp.height_mm), bounds_mm)],
           "centred_fit": [str(hp) for hp in machine.hoops_fitting(w, h)],
           "header_hoop": None}
    if ext == "jef":
        code = jef_header_hoop(path)
        field = JEF_HOOP_CODES.get(code)
        out["header_hoop"] = {
            "code": code, "field_mm": None if field is None else list(field),
            "catalogue_hoops": [hp.name for hp in machine.hoops if hp.jef_code == code],
            "holds_stitches": None if field is None else _holds(field, bounds_mm)}
    return out


def summarise(path, machine=None) -> dict:
    """Counts, stitch extents about the hoop centre (mm) and the hoops of ``machine`` (a
    ``machines.Machine``; default: the built-in default machine) that hold the embroidery
    file ``path`` (see the module docstring)."""
    import pyembroidery as pe

    from stitchswitch.layout.embroidery.machines import default_machine

    machine = default_machine() if machine is None else machine
    path = pathlib.Path(path)
    where = repr(clip(str(path), 200))
    if not path.is_file():
        raise InvalidInputError(f"no such file: {where}")
    ext = path.suffix.lower().lstrip(".")
    readable = _reader_extensions()
    if ext not in readable:
        raise InvalidInputError(f"{where}: {clip(ext) or 'no extension'!r} is not an embroidery "
                                f"format pyembroidery reads ({', '.join(readable[:12])}, ...)")
    try:
        _check_header(path, ext, where)
    except OSError as exc:
        raise InvalidInputError(f"{where}: cannot be read ({exc.strerror or exc})") from None
    pattern = _read(path, ext, where)
    stitches = [s for s in pattern.stitches if isinstance(s, (list, tuple)) and len(s) >= 3
                and all(isinstance(v, (int, float)) for v in s[:3])]
    cmds = [int(s[2]) & pe.COMMAND_MASK for s in stitches]
    n_stitch = cmds.count(pe.STITCH)
    if n_stitch == 0:
        raise InvalidInputError(f"{where}: holds no stitches (not a {ext.upper()} design)")
    xs = [float(s[0]) / 10.0 for s in stitches]
    ys = [-float(s[1]) / 10.0 for s in stitches]            # y down in the file, up here
    if not all(math.isfinite(v) for v in xs + ys):
        raise InvalidInputError(f"{where}: a stitch coordinate is not finite")
    sx = [x for x, c in zip(xs, cmds) if c == pe.STITCH]
    sy = [y for y, c in zip(ys, cmds) if c == pe.STITCH]
    bounds = (min(sx) + 0.0, min(sy) + 0.0, max(sx) + 0.0, max(sy) + 0.0)
    w, h = bounds[2] - bounds[0], bounds[3] - bounds[1]
    if w == 0.0 and h == 0.0:
        raise InvalidInputError(f"{where}: all {n_stitch} stitches lie at one point (not a "
                                f"{ext.upper()} design)")
    return {"stitches": n_stitch, "jumps": cmds.count(pe.JUMP), "trims": cmds.count(pe.TRIM),
            "colour_changes": cmds.count(pe.COLOR_CHANGE),
            "colours": max(len(pattern.threadlist), cmds.count(pe.COLOR_CHANGE) + 1),
            "width_mm": w, "height_mm": h, "stitch_bounds_mm": list(bounds),
            "span_bounds_mm": [min(xs) + 0.0, min(ys) + 0.0, max(xs) + 0.0, max(ys) + 0.0],
            **_hoop_report(machine, bounds, ext, path)}
