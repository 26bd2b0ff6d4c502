"""An output directory written as a whole: built beside the target, renamed into place.

``check_outdir`` refuses, before any work, a target that is not a directory or that holds
anything, unless ``force``. ``write_outdir`` writes every file into a fresh temporary directory
next to the target (same file system), then renames it to the target: an absent or empty target
is simply replaced; with ``force`` an existing one is moved aside, the new one renamed in and
the old one deleted (on a failed rename the old one is put back). On any error the temporary
directory is removed, so nothing half-written is ever left.
"""
from __future__ import annotations

import contextlib
import os
import secrets
import shutil
from pathlib import Path

from stitchswitch.atomic import atomic_write_bytes
from stitchswitch.errors import InvalidInputError


def check_outdir(outdir, force: bool = False) -> None:
    out = Path(outdir)
    where = f"output directory {os.fspath(outdir)!r}"
    parent = out.absolute().parent
    if not parent.is_dir():
        raise InvalidInputError(f"{where}: the parent directory {str(parent)!r} does not exist")
    if not out.exists() and not out.is_symlink():
        return
    if out.is_symlink() or not out.is_dir():
        raise InvalidInputError(f"{where}: exists and is not a directory")
    if any(out.iterdir()) and not force:
        raise InvalidInputError(f"{where}: is not empty; give a new or empty directory, or "
                                "--force to replace it")


def _new_dir_next_to(out: Path, tag: str) -> Path:
    for _ in range(100):
        tmp = out.absolute().parent / f".{out.name}.{secrets.token_hex(6)}.{tag}"
        try:
            os.mkdir(tmp, 0o777)
            return tmp
        except FileExistsError:
            continue
    raise FileExistsError(f"could not create a temporary directory next to {str(out)!r}")


def _place(tmp: Path, out: Path) -> None:
    if out.is_dir() and not any(out.iterdir()):
        out.rmdir()
    if not out.exists():
        os.rename(tmp, out)
        return
    old = _new_dir_next_to(out, "old")
    old.rmdir()
    os.rename(out, old)
    try:
        os.rename(tmp, out)
    except BaseException:
        os.rename(old, out)
        raise
    shutil.rmtree(old, ignore_errors=True)


def write_outdir(outdir, files, force: bool = False) -> None:
    """Write ``files`` (name -> bytes, or a callable returning bytes, evaluated here so that
    its errors also leave nothing behind) as the directory ``outdir``."""
    out = Path(outdir)
    check_outdir(out, force)
    tmp = _new_dir_next_to(out, "tmp")
    try:
        for name, data in files.items():
            if Path(name).name != name:
                raise InvalidInputError(f"output file name {name!r} must not contain a folder")
            atomic_write_bytes(tmp / name, data() if callable(data) else data)
        check_outdir(out, force)              # still acceptable after the work?
        _place(tmp, out)
    except BaseException:
        with contextlib.suppress(OSError):
            shutil.rmtree(tmp)
        raise


@contextlib.contextmanager
def building(outdir, force: bool = False):
    """Build a directory in place of ``outdir``: yields a fresh temporary directory next to it
    (write anything into it, sub-folders included); on success it is renamed to ``outdir`` as
    ``write_outdir`` does, on any error it is removed."""
    out = Path(outdir)
    check_outdir(out, force)
    tmp = _new_dir_next_to(out, "tmp")
    try:
        yield tmp
        check_outdir(out, force)
        _place(tmp, out)
    except BaseException:
        with contextlib.suppress(OSError):
            shutil.rmtree(tmp)
        raise
