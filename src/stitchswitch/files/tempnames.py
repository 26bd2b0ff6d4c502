"""Names of the temporary files and folders the package writes next to a target, and the
removal of those a killed writer left behind.

Every temporary entry next to ``target`` is called ``.<target name>.<pid>-<12 hex>.<tag>``
(tag ``tmp`` or ``old``), the pid being the writer's. A process killed by SIGKILL cannot remove
its temporary entries, so every write to a target first calls ``remove_stale(target)``, which
removes the entries of that naming whose writer no longer runs. The test is by process id on
this machine: a folder shared with writers on other hosts is not supported. Anything not of
exactly this naming (a user's own dot-files) is never touched.
"""
from __future__ import annotations

import os
import secrets
import shutil
from pathlib import Path

__all__ = ["temp_path", "remove_stale"]

_TAGS = (".tmp", ".old")


def temp_path(target, tag: str = "tmp") -> Path:
    """A fresh name next to ``target`` for a temporary entry of this process (not created)."""
    out = Path(os.path.abspath(os.fspath(target)))
    return out.parent / f".{out.name}.{os.getpid()}-{secrets.token_hex(6)}.{tag}"


def _writer_pid(target_name: str, entry_name: str) -> int | None:
    """The writer's pid if ``entry_name`` is a temporary entry of ``target_name``, else None."""
    prefix = f".{target_name}."
    if not (entry_name.startswith(prefix) and entry_name.endswith(_TAGS)):
        return None
    pid, sep, token = entry_name[len(prefix):-4].partition("-")
    if not (sep and pid.isdigit() and len(token) == 12
            and all(c in "0123456789abcdef" for c in token)):
        return None
    return int(pid)


def _running(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:           # another user's process: alive
        return True
    return True


def remove_stale(target) -> list[Path]:
    """Remove the temporary files and folders next to ``target`` left by writers that no
    longer run (our own naming only); return them."""
    out = Path(os.path.abspath(os.fspath(target)))
    removed = []
    try:
        entries = list(out.parent.iterdir())
    except OSError:
        return removed
    for entry in entries:
        pid = _writer_pid(out.name, entry.name)
        if pid is None or _running(pid):
            continue
        try:
            if entry.is_dir() and not entry.is_symlink():
                shutil.rmtree(entry)
            else:
                entry.unlink()
        except OSError:
            continue
        removed.append(entry)
    return removed
