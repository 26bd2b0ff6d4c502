"""Saving the studio's design and its autosave sidecar.

``Document`` remembers the bytes of the design file as loaded: saving a design without changes
writes those bytes back, so it is byte-identical to the file loaded even when that file was
not in canonical form; a changed design is written by ``design_io.save_design`` (canonical,
validated, atomic). The autosave sidecar ``<design>.autosave.json`` is written atomically after
every edit and removed by a save, so a closed tab or a crash loses at most the last edit.
"""
from __future__ import annotations

import os

from stitchswitch.files.atomic import atomic_write_bytes, atomic_write_text
from stitchswitch.layout.garment.design import Design
from stitchswitch.layout.garment.design_io import dumps_design, load_design

SIDECAR_SUFFIX = ".autosave.json"


def sidecar_path(path) -> str:
    return os.fspath(path) + SIDECAR_SUFFIX


class Document:
    """The design file the studio edits: ``path`` (where it saves) and the loaded state."""

    def __init__(self, path, design: Design, loaded_bytes: bytes | None = None):
        self.path = os.fspath(path)
        self.loaded = design
        self.loaded_bytes = loaded_bytes

    @classmethod
    def open(cls, path) -> tuple["Document", Design]:
        design = load_design(path)
        with open(path, "rb") as f:
            raw = f.read()
        return cls(path, design, raw), design

    def dirty(self, design: Design) -> bool:
        """True if ``design`` differs from what the file holds."""
        return self.loaded_bytes is None or design != self.loaded

    def save(self, design: Design) -> None:
        if self.loaded_bytes is not None and design == self.loaded:
            atomic_write_bytes(self.path, self.loaded_bytes)
        else:
            text = dumps_design(design)
            atomic_write_text(self.path, text)
            self.loaded_bytes = text.encode("utf-8")
        self.loaded = design
        self.discard_autosave()

    def autosave(self, design: Design) -> None:
        atomic_write_text(sidecar_path(self.path), dumps_design(design))

    def discard_autosave(self) -> None:
        try:
            os.remove(sidecar_path(self.path))
        except FileNotFoundError:
            pass

    def recover(self) -> Design | None:
        """The autosaved design, if a sidecar exists (None otherwise)."""
        side = sidecar_path(self.path)
        return load_design(side) if os.path.exists(side) else None
