"""Output directories written as a whole: built beside the target, renamed into place.

``check_outdir`` refuses, before any work, a target that is not a directory or that holds
anything, unless ``force`` or unless ``previous`` recognises it as an earlier output of the same
tool (which is then replaced). ``building`` yields a fresh temporary directory next to the target
(same file system); when the block ends it is renamed to the target (an absent or empty target is
simply replaced; an existing one is moved aside, the new one renamed in and the old one deleted,
and put back if the rename fails). On any error the temporary directory is removed, so nothing
half-written is ever left. ``write_outdir`` writes a dict of files that way.

A process killed mid-write (SIGKILL) cannot remove its temporary directory. Their names carry
the writer's process id (``.<target>.<pid>-<hex>.tmp``, ``files.tempnames``), so ``building``
first removes the temporary entries next to its target whose writer no longer runs
(``remove_stale``).
"""
from __future__ import annotations

import contextlib
import os
import shutil
from pathlib import Path
from typing import Callable

from stitchswitch.errors import InvalidInputError
from stitchswitch.files.atomic import atomic_write_bytes
from stitchswitch.files.tempnames import remove_stale, temp_path

__all__ = ["check_outdir", "building", "write_outdir", "previous_output", "remove_stale",
           "new_dir_next_to"]

#: ``previous(path) -> None`` if the non-empty directory ``path`` is an earlier output of this
#: tool (so it may be replaced), else the reason it is not, e.g. "holds 'x.txt', not from this
#: tool".
Previous = Callable[[Path], "str | None"]


def check_outdir(outdir, force: bool = False, previous: Previous | None = None,
                 what: str = "output directory") -> bool:
    """Raise ``InvalidInputError`` unless ``outdir`` may be written; True if it holds an
    earlier output that will be replaced."""
    out = Path(outdir)
    where = f"{what} {os.fspath(outdir)!r}"
    parent = out.absolute().parent
    if parent.exists() and not parent.is_dir():
        raise InvalidInputError(f"{where}: {str(parent)!r} is not a directory")
    if not parent.is_dir():
        raise InvalidInputError(f"{where}: the parent directory {str(parent)!r} does not exist")
    try:
        new_dir_next_to(out, "tmp").rmdir()          # can we create the folder beside it?
    except OSError as exc:
        raise InvalidInputError(f"{where}: cannot write in the directory {str(parent)!r} "
                                f"({exc.strerror or type(exc).__name__})") from None
    if not out.exists() and not out.is_symlink():
        return False
    if out.is_symlink() or not out.is_dir():
        raise InvalidInputError(f"{where}: exists and is not a directory")
    if not any(out.iterdir()):
        return False
    if force:
        return True
    if previous is None:
        raise InvalidInputError(f"{where}: is not empty; give a new or empty directory, or "
                                "--force to replace it")
    reason = previous(out)
    if reason is not None:
        raise InvalidInputError(f"{where}: {reason}")
    return True


def new_dir_next_to(out, tag: str = "tmp") -> Path:
    """Create a fresh temporary directory of this process next to ``out`` (``tempnames``)."""
    for _ in range(100):
        tmp = temp_path(out, tag)
        try:
            os.mkdir(tmp, 0o777)          # the umask applies, as for a plain mkdir
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
    old = new_dir_next_to(out, "old")
    old.rmdir()
    os.rename(out, old)
    try:
        os.rename(tmp, out)
    except BaseException:
        os.rename(old, out)
        raise
    shutil.rmtree(old, ignore_errors=True)


@contextlib.contextmanager
def building(outdir, force: bool = False, previous: Previous | None = None,
             what: str = "output directory"):
    """Yield a temporary directory to fill (sub-folders allowed); it becomes ``outdir``. An
    ``OSError`` while writing or placing it becomes an ``InvalidInputError`` naming ``outdir``."""
    out = Path(outdir)
    check_outdir(out, force, previous, what)
    remove_stale(out)
    tmp = new_dir_next_to(out, "tmp")
    try:
        yield tmp
        check_outdir(out, force, previous, what)          # still acceptable after the work?
        _place(tmp, out)
    except BaseException as exc:
        with contextlib.suppress(OSError):
            shutil.rmtree(tmp)
        if isinstance(exc, OSError):
            raise InvalidInputError(f"{what} {os.fspath(outdir)!r}: cannot be written "
                                    f"({exc.strerror or type(exc).__name__})") from None
        raise


def write_outdir(outdir, files, force: bool = False, previous: Previous | None = None) -> None:
    """Write ``files`` (name -> bytes, or a callable returning bytes, evaluated inside, so that
    its errors also leave nothing behind) as the directory ``outdir``."""
    with building(outdir, force, previous) as tmp:
        for name, data in files.items():
            if Path(name).name != name:
                raise InvalidInputError(f"output file name {name!r} must not contain a folder")
            atomic_write_bytes(tmp / name, data() if callable(data) else data)


def previous_output(files, generator: str, noun: str = "report") -> Previous:
    """A ``previous`` test for tools that write a fixed set of ``files`` including a
    ``report.json`` whose ``"generator"`` is ``generator``."""
    import json

    def test(out: Path) -> str | None:
        entries = sorted(p.name for p in out.iterdir())
        foreign = [e for e in entries if e not in files]
        try:
            ours = json.loads((out / "report.json").read_text("utf-8")).get("generator") == generator
        except (OSError, ValueError, AttributeError):
            ours = False
        if foreign or not ours:
            why = (f"holds {foreign[0]!r}, not from this tool" if foreign
                   else "is not empty and holds no report.json of this tool")
            return f"{why}; give an empty or new directory, or one holding a previous {noun}"
        return None
    return test
