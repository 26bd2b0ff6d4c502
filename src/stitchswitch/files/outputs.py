"""Output files: checked before any work, and every file of one command written as one unit.

``check_output_file(path, ...)`` refuses, with one ``InvalidInputError`` naming the path as the
user gave it, an output that cannot be written: an empty path, a path that is a directory, a
parent that does not exist or is not a directory, a directory this process cannot create files
in (tested by creating and removing a temporary file there, so that a read-only file system and
a root user are judged right), or an extension not in ``allowed``. Commands call it (through
the CLI's ``OutputFile`` option type) before computing anything.

``together({"out": path, "plot": path_or_None, ...})`` is a context manager for the files one
command writes. It yields the same keys mapped to temporary paths to write instead: each is
``<temporary folder next to the target>/<the target's own name>``, so writers that choose a
format by the extension keep working. When the block ends, every file is moved into place; if
the block raises, or any move fails, every target is left as it was before (files already
replaced are put back) and the temporaries are removed. An ``OSError`` (disk full, a folder
removed meanwhile) becomes an ``InvalidInputError`` naming the user's path, never a temporary
one. A run killed by SIGKILL leaves each target either old or complete and new; its temporary
folders (named with its pid, ``files.tempnames``) are removed by the next write to the target.
"""
from __future__ import annotations

import contextlib
import os
import shutil
from pathlib import Path
from typing import Mapping

from stitchswitch.errors import InvalidInputError
from stitchswitch.files.extensions import check_extension
from stitchswitch.files.outdir import new_dir_next_to
from stitchswitch.files.shown import clip
from stitchswitch.files.tempnames import remove_stale, temp_path

__all__ = ["check_output_file", "check_distinct", "together"]


def _shown(path) -> str:
    """A path as messages quote it (long ones shortened)."""
    return repr(clip(os.fspath(path), 160))


def _reason(exc: OSError) -> str:
    return exc.strerror or type(exc).__name__


def check_output_file(path, allowed: tuple[str, ...] | None = None, what: str = "output",
                      hint: str = "") -> Path:
    """``path`` as a ``Path`` if a file can be written there, else an ``InvalidInputError``
    naming ``what`` and ``path``."""
    text = os.fspath(path)
    where = f"{what} {_shown(text)}"
    if not text.strip():
        raise InvalidInputError(f"{what}: the path is empty")
    out = Path(text)
    if out.is_dir():
        raise InvalidInputError(f"{where}: is a directory; give a file name")
    parent = out.absolute().parent
    if not parent.exists():
        raise InvalidInputError(f"{where}: the directory {_shown(str(parent))} does not exist")
    if not parent.is_dir():
        raise InvalidInputError(f"{where}: {_shown(str(parent))} is not a directory")
    if allowed is not None:
        check_extension(text, allowed, what, hint)
    probe = temp_path(out)
    try:
        fd = os.open(probe, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o600)
    except OSError as exc:
        raise InvalidInputError(f"{where}: cannot write in the directory {_shown(str(parent))} "
                                f"({_reason(exc)})") from None
    os.close(fd)
    with contextlib.suppress(OSError):
        os.unlink(probe)
    return out


def check_distinct(paths: Mapping[str, object]) -> None:
    """Refuse two outputs of one command that name the same file (``what -> path or None``)."""
    seen: dict[str, str] = {}
    for what, path in paths.items():
        if path is None:
            continue
        key = os.path.normcase(os.path.realpath(os.fspath(path)))
        if key in seen:
            raise InvalidInputError(f"{what} {_shown(os.fspath(path))}: the same file as "
                                    f"{seen[key]}; give each output its own file")
        seen[key] = what


class _Staged(dict):
    """The temporary paths of ``together``; remembers the last one asked for (the file being
    written when an ``OSError`` names no file)."""

    last = None

    def __getitem__(self, what):
        self.last = what
        return super().__getitem__(what)


def _user_path(exc: OSError, stages: dict[str, tuple[Path, Path]], user: dict[str, str],
               last) -> str:
    """The output an ``OSError`` is about, as the user named it: the one whose temporary folder
    or target it names, else the one last asked for, else the first."""
    named = os.fspath(exc.filename) if exc.filename is not None else ""
    for what, (stage, target) in stages.items():
        if named.startswith(os.fspath(stage)) or named == os.fspath(target):
            return f"{what} {_shown(user[what])}"
    what = last if last in user else next(iter(user))
    return f"{what} {_shown(user[what])}"


def _commit(stages: dict[str, tuple[Path, Path]]) -> None:
    """Move every staged file into place; on any failure put back what was there before."""
    done: list[tuple[Path, Path | None]] = []
    try:
        for what, (stage, target) in stages.items():
            new = stage / target.name
            if not new.is_file():
                raise InvalidInputError(f"{what} {_shown(target)}: nothing was written")
            backup = None
            if target.is_file():
                backup = stage / f"{target.name}.previous"
                try:
                    os.link(target, backup)
                except OSError:
                    shutil.copy2(target, backup)
            os.replace(new, target)
            done.append((target, backup))
    except BaseException:
        for target, backup in reversed(done):
            with contextlib.suppress(OSError):
                if backup is None:
                    os.unlink(target)
                else:
                    os.replace(backup, target)
        raise


@contextlib.contextmanager
def together(paths: Mapping[str, object]):
    """Yield ``what -> temporary path`` for every ``what -> target`` whose target is not None;
    the files written there replace the targets together when the block ends (see above)."""
    targets = {what: Path(os.path.abspath(os.fspath(p))) for what, p in paths.items()
               if p is not None}
    user = {what: os.fspath(p) for what, p in paths.items() if p is not None}
    check_distinct(user)
    stages: dict[str, tuple[Path, Path]] = {}
    staged = _Staged()
    try:
        for what, target in targets.items():
            remove_stale(target)
            stages[what] = (new_dir_next_to(target), target)
            dict.__setitem__(staged, what, stages[what][0] / target.name)
        yield staged
        _commit(stages)
    except OSError as exc:
        if not user:
            raise
        raise InvalidInputError(f"{_user_path(exc, stages, user, staged.last)}: cannot be written "
                                f"({_reason(exc)})") from None
    finally:
        for stage, _ in stages.values():
            shutil.rmtree(stage, ignore_errors=True)
