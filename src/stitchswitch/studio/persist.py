"""Saving the studio's design and its autosave sidecar, and finding a reopened design's pattern.

``Document`` remembers the bytes of the design file as loaded: saving a design without changes
writes those bytes back, so it is byte-identical to the file loaded even when that file was
not in canonical form; a changed design is written by ``design_io.save_design`` (canonical,
validated, atomic). The autosave sidecar ``<design>.autosave.json`` is written atomically after
every edit and removed by a save, so a closed tab or a crash loses at most the last edit.

A design file records where its pieces came from: each piece's ``source`` is the pattern file it
was imported from (``stitchswitch import`` writes its file name; the studio writes its path
relative to the design file) and its ``size``. ``source_pattern`` finds that pattern again
relative to the design file, so a reopened design offers the pattern's sizes; nothing is added
to the file, so a design saved without changes stays byte-identical.
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


def source_pattern(design: Design, design_path) -> tuple[tuple | None, str]:
    """(pattern, note): every piece (all sizes, ``dxf.reader.Piece``) of the pattern file the
    design's pieces name as their ``source``, looked up relative to the design file, when it
    holds the design's size and piece names; else (None, why not; "" for a design whose pieces
    name no pattern file)."""
    sources = {p.source for p in design.pieces}
    if len(sources) != 1 or not next(iter(sources)).lower().endswith(".dxf"):
        return None, ""
    source = next(iter(sources))
    path = os.path.join(os.path.dirname(os.path.abspath(design_path)), source)
    if not os.path.isfile(path):
        return None, f"the pattern {source!r} of its pieces is not at {path!r}: no size picker"
    from stitchswitch.errors import StitchSwitchError
    from stitchswitch.layout.garment.dxf.reader import import_dxf

    try:
        pattern = tuple(import_dxf(path))
    except (StitchSwitchError, OSError) as exc:
        return None, f"the pattern {path!r} cannot be read ({exc}): no size picker"
    size = design.pieces[0].size
    names = {p.name for p in pattern if p.size == size}
    missing = [p.name for p in design.pieces if p.name.split(" #")[0] not in names]
    if missing:
        return None, (f"the pattern {path!r} has no piece {missing[0]!r} in size {size!r}: "
                      "no size picker")
    return pattern, ""
