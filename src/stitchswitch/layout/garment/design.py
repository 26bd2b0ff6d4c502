"""The design: garment pieces and the patches placed on them (the design file, docs/design-file.md).

Coordinates: piece outlines and patch centres are garment coordinates in mm on the relaxed
fabric, as imported from the pattern. A patch's ``diameter_mm`` and ``fill`` are the model's: d
is measured on the pre-stretched (hooped) fabric, so the flat relaxed footprint of a patch has
diameter d / eta (eta = ``material.eta``, 1.7 by default) and its ``outline_mm`` is in stretched
(hoop) mm relative to the patch centre.

The objects are plain frozen records; ``design_io`` reads, validates and writes them. Arrays are
stored as read-only float copies, and equality compares them by value.
"""
from __future__ import annotations

import os
from dataclasses import dataclass, field, fields, replace

import numpy as np

from stitchswitch.errors import InvalidInputError
from stitchswitch.layout.embroidery.machines import DEFAULT_MACHINE

VERSION = 1
STATES = ("up", "down")


def _frozen_array(value) -> np.ndarray:
    arr = np.array(value, dtype=float)       # a copy: the caller's array stays theirs
    arr.setflags(write=False)
    return arr


def _equal(a, b) -> bool:
    """Field equality with arrays compared by value."""
    if isinstance(a, np.ndarray) or isinstance(b, np.ndarray):
        if a is None or b is None:
            return False
        return a.shape == b.shape and bool(np.array_equal(a, b))
    return a == b


class _ArrayEq:
    """Value equality over all dataclass fields, arrays included (not hashable)."""

    def __eq__(self, other):
        if type(other) is not type(self):
            return NotImplemented
        return all(_equal(getattr(self, f.name), getattr(other, f.name)) for f in fields(self))

    __hash__ = None


@dataclass(frozen=True, eq=False)
class PieceSpec(_ArrayEq):
    """A garment piece: a closed outline (n, 2) in relaxed garment mm, last point not repeated."""
    name: str
    size: str
    source: str
    outline_mm: np.ndarray

    def __post_init__(self):
        object.__setattr__(self, "outline_mm", _frozen_array(self.outline_mm))


@dataclass(frozen=True)
class CompositeSpec:
    """A concentric core disc of ``core_diameter_mm`` (stretched mm) stitched at ``core_fill``."""
    core_diameter_mm: float
    core_fill: float


@dataclass(frozen=True)
class Threads:
    """Thread colours as ``#rrggbb``."""
    top: str = "#1b1b1b"
    conductive: str = "#b0b0b0"


@dataclass(frozen=True, eq=False)
class PatchSpec(_ArrayEq):
    """One patch. ``centre_mm``: relaxed garment mm; ``diameter_mm``: pre-stretched mm;
    ``outline_mm``: optional (k, 2) polygon in stretched mm relative to the centre."""
    id: str
    piece: str
    centre_mm: tuple[float, float]
    diameter_mm: float
    fill: float
    composite: CompositeSpec | None = None
    outline_mm: np.ndarray | None = None
    conductive: str | None = None
    threads: Threads = field(default_factory=Threads)
    state: str = "up"

    def __post_init__(self):
        x, y = self.centre_mm
        object.__setattr__(self, "centre_mm", (float(x), float(y)))
        object.__setattr__(self, "diameter_mm", float(self.diameter_mm))
        object.__setattr__(self, "fill", float(self.fill))
        if self.outline_mm is not None:
            object.__setattr__(self, "outline_mm", _frozen_array(self.outline_mm))

    @property
    def radius_mm(self) -> float:
        """Half the diameter, in stretched (hoop) mm."""
        return self.diameter_mm / 2.0

    def replace(self, **changes) -> "PatchSpec":
        return replace(self, **changes)


@dataclass(frozen=True)
class MaterialRef:
    """The built-in material by ``name`` ("default"), or a material JSON ``file`` (a relative
    path is relative to the design file's folder)."""
    name: str | None = "default"
    file: str | None = None


@dataclass(frozen=True)
class MachineSpec:
    """The embroidery machine and, optionally, the hoop to use (None: chosen per hooping)."""
    name: str = DEFAULT_MACHINE
    hoop: str | None = None


@dataclass(frozen=True, eq=False)
class Design(_ArrayEq):
    """A whole design. ``path`` is the file it was read from (None if built in memory); it is
    not part of the file and not compared. ``blank_margin_mm`` (relaxed garment mm): 0 when
    every piece is hooped already cut out (the hoop frame must clamp the piece itself); more
    when each piece is hooped as an uncut blank extending that far past its outline, so a hoop
    may reach over the outline onto the blank."""
    version: int
    pieces: tuple[PieceSpec, ...]
    patches: tuple[PatchSpec, ...]
    material: MaterialRef = field(default_factory=MaterialRef)
    machine: MachineSpec = field(default_factory=MachineSpec)
    path: str | None = None
    blank_margin_mm: float = 0.0

    def __post_init__(self):
        object.__setattr__(self, "pieces", tuple(self.pieces))
        object.__setattr__(self, "patches", tuple(self.patches))

    def __eq__(self, other):
        if type(other) is not type(self):
            return NotImplemented
        return (self.version == other.version and self.pieces == other.pieces
                and self.patches == other.patches and self.material == other.material
                and self.machine == other.machine
                and self.blank_margin_mm == other.blank_margin_mm)

    __hash__ = None

    def piece(self, name: str) -> PieceSpec:
        for p in self.pieces:
            if p.name == name:
                return p
        raise InvalidInputError(f"no piece named {name!r}; the pieces are "
                                + (", ".join(p.name for p in self.pieces) or "(none)"))

    def patch(self, patch_id: str) -> PatchSpec:
        for p in self.patches:
            if p.id == patch_id:
                return p
        ids = [p.id for p in self.patches]
        listed = ", ".join(ids[:20]) + (", ..." if len(ids) > 20 else "")
        raise InvalidInputError(f"no patch with id {patch_id!r}; the patches are "
                                + (listed or "(none)"))

    def with_patches(self, patches) -> "Design":
        """A copy with the patch list replaced (not validated: ``design_io.validate`` does)."""
        return replace(self, patches=tuple(patches))

    def material_path(self) -> str | None:
        """The material file, resolved against the design file's folder (None: built-in)."""
        if self.material.file is None:
            return None
        f = os.path.expanduser(self.material.file)
        if not os.path.isabs(f) and self.path is not None:
            f = os.path.join(os.path.dirname(os.path.abspath(self.path)), f)
        return f

    def material_object(self):
        """The ``reduced.model.params.Material`` this design refers to."""
        from stitchswitch.reduced.model.material_io import load_material
        from stitchswitch.reduced.model.params import DEFAULT_MATERIAL

        path = self.material_path()
        if path is None:
            if self.material.name != "default":
                raise InvalidInputError(f"material.name: unknown material {self.material.name!r} "
                                        "(the built-in material is 'default')")
            return DEFAULT_MATERIAL
        try:
            return load_material(path)
        except InvalidInputError as exc:
            raise InvalidInputError(f"material.file: {exc}") from None
