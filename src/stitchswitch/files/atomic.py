"""Atomic file writes: a reader sees either the old file or the complete new one, never a part.

The data go to a temporary file in the target's directory (same file system, so the final
``os.replace`` is an atomic rename), are flushed and fsync'ed, then renamed over the target. On
any error, including KeyboardInterrupt, the temporary file is removed and the error re-raised;
an existing target is left untouched.

The temporary file is named ``.<name>.<pid>-<hex>.tmp`` (``files.tempnames``): a writer killed
by SIGKILL cannot remove it, so every write first removes the ones of writers that no longer
run.

The temporary file is created with mode 0o666 minus the umask, like ``open(path, "w")``; the
mode of a file being replaced is not preserved. Text is written as UTF-8 with no newline
translation, so the bytes on disk are the same on every platform.
"""
from __future__ import annotations

import contextlib
import os

from stitchswitch.files.tempnames import remove_stale, temp_path

__all__ = ["atomic_write_bytes", "atomic_write_text"]


def _create_temp(path: str) -> tuple[int, str]:
    """Open a new, exclusively created temporary file next to ``path``."""
    for _ in range(100):
        tmp = os.fspath(temp_path(path))
        try:
            return os.open(tmp, os.O_WRONLY | os.O_CREAT | os.O_EXCL | getattr(os, "O_BINARY", 0),
                           0o666), tmp
        except FileExistsError:
            continue
    raise FileExistsError(f"could not create a temporary file next to {path!r}")


def _fsync_directory(directory: str) -> None:
    """Make the rename durable (POSIX); best effort, a no-op where directories cannot be opened."""
    with contextlib.suppress(OSError, AttributeError):
        fd = os.open(directory, os.O_RDONLY)
        try:
            os.fsync(fd)
        finally:
            os.close(fd)


def atomic_write_bytes(path: str | os.PathLike, data: bytes) -> None:
    """Replace the file at ``path`` by ``data`` atomically."""
    path = os.fspath(path)
    remove_stale(path)
    fd, tmp = _create_temp(path)
    try:
        with os.fdopen(fd, "wb") as f:
            f.write(data)
            f.flush()
            os.fsync(f.fileno())
        os.replace(tmp, path)
    except BaseException:
        with contextlib.suppress(OSError):
            os.unlink(tmp)
        raise
    _fsync_directory(os.path.dirname(os.path.abspath(path)))


def atomic_write_text(path: str | os.PathLike, text: str, encoding: str = "utf-8") -> None:
    """Replace the file at ``path`` by ``text`` (encoded, newlines untranslated) atomically."""
    atomic_write_bytes(path, text.encode(encoding))
