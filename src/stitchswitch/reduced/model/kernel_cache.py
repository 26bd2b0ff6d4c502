"""Keep numba's on-disk cache of the compiled kernels consistent with their sources.

numba's cache (``cache=True``) checks only the file that defines a compiled function, not the
files of the functions it calls (a documented limitation). The solver's fused energy and Newton
loop call the term kernels of other modules, so after an edit of a kernel module alone (a
``git pull`` into an editable install, a developer's change) they would keep running the old
kernel. ``clear_if_changed`` fingerprints every kernel source and, when the fingerprint differs
from the one recorded beside the cache, removes the cached machine code of those folders, so
numba compiles afresh. It runs when the terms package is imported, before any kernel is loaded.
A read-only installation (where numba keeps its cache elsewhere and files never change) is left
alone.
"""
from __future__ import annotations

import hashlib
import os
from pathlib import Path

__all__ = ["clear_if_changed", "kernel_sources"]

STAMP = "numba-kernel-sources.sha256"


def kernel_sources(reduced: Path) -> list[Path]:
    """Every module whose compiled code may be inlined into another's: the terms and solvers."""
    return sorted((reduced / "model" / "terms").rglob("*.py")) + sorted((reduced / "solvers").glob("*.py"))


def fingerprint(files: list[Path], root: Path) -> str:
    h = hashlib.sha256()
    for f in files:
        h.update(str(f.relative_to(root)).encode() + b"\0" + f.read_bytes() + b"\0")
    return h.hexdigest()


def clear_if_changed(files: list[Path], stamp: Path) -> bool:
    """Remove the numba cache files (``*.nbi``, ``*.nbc``) beside ``files`` if their sources
    changed since ``stamp`` was written, then record the new fingerprint. True if it cleared."""
    digest = fingerprint(files, stamp.parent.parent)
    try:
        if stamp.read_text() == digest:
            return False
    except OSError:
        pass
    try:
        for folder in sorted({f.parent / "__pycache__" for f in files}):
            for cached in list(folder.glob("*.nbi")) + list(folder.glob("*.nbc")):
                cached.unlink(missing_ok=True)
        stamp.parent.mkdir(exist_ok=True)
        tmp = stamp.with_name(f"{stamp.name}.{os.getpid()}.tmp")
        tmp.write_text(digest)
        os.replace(tmp, stamp)
    except OSError:             # read-only install: numba caches elsewhere, sources do not change
        return False
    return True


def guard() -> None:
    """``clear_if_changed`` for this installation's kernels."""
    reduced = Path(__file__).resolve().parent.parent
    clear_if_changed(kernel_sources(reduced), reduced / "__pycache__" / STAMP)
