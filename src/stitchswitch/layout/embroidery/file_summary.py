"""What an embroidery file from anywhere holds: stitch, jump, trim and colour counts, extents,
and the hoops of the default machine it fits (``stitchswitch inspect``).

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

__all__ = ["MAX_EMBROIDERY_BYTES", "summarise"]

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


def summarise(path) -> dict:
    """Counts, extents (mm) and fitting hoops of the embroidery file ``path``."""
    import pyembroidery as pe

    from stitchswitch.layout.embroidery.machines import default_machine

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
    xs = [float(s[0]) for s in stitches]
    ys = [float(s[1]) for s in stitches]
    if not all(math.isfinite(v) for v in xs + ys):
        raise InvalidInputError(f"{where}: a stitch coordinate is not finite")
    w, h = (max(xs) - min(xs)) / 10.0, (max(ys) - min(ys)) / 10.0
    if w == 0.0 and h == 0.0:
        raise InvalidInputError(f"{where}: all {n_stitch} stitches lie at one point (not a "
                                f"{ext.upper()} design)")
    return {"stitches": n_stitch, "jumps": cmds.count(pe.JUMP), "trims": cmds.count(pe.TRIM),
            "colour_changes": cmds.count(pe.COLOR_CHANGE),
            "colours": max(len(pattern.threadlist), cmds.count(pe.COLOR_CHANGE) + 1),
            "width_mm": w, "height_mm": h,
            "hoops": [str(hp) for hp in default_machine().hoops_fitting(w, h)]}
