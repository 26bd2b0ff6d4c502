"""What a fabrication folder says, as frozen dataclasses: ``FabricationDoc`` and its parts.

``layout.fabrication.fabricate`` builds one; ``as_dict`` gives the content of fabrication.json
(keys in a fixed order, optional keys left out where they do not apply; the flat records are
written field by field, ``dataclasses.asdict``), and the sheet
(``layout.fabrication.sheet``) and the demo summary read the same object, so all of them agree.
Lengths are in mm, times in minutes, thread in metres, as the field names say.
"""
from __future__ import annotations

from dataclasses import asdict, dataclass

from stitchswitch.layout.embroidery.jef_palette import JefThread

#: the layout of fabrication.json (docs/fabrication.md): 2 adds each thread's ``jef_thread``;
#: files without ``schema`` are layout 1
SCHEMA = 2

__all__ = ["SCHEMA", "DesignFile", "MachineInfo", "StretchInfo", "GroupingInfo", "Conflict",
           "HoopingFiles", "PlacedPatch", "Thread", "HoopingDoc", "Totals", "FabricationDoc"]


@dataclass(frozen=True)
class DesignFile:
    file: str
    sha256: str | None


@dataclass(frozen=True)
class MachineInfo:
    name: str
    label: str
    stitches_per_minute: float
    source: str


@dataclass(frozen=True)
class StretchInfo:
    eta: float
    instructions: tuple[str, ...]

    def as_dict(self) -> dict:
        return {"eta": self.eta, "instructions": list(self.instructions)}


@dataclass(frozen=True)
class GroupingInfo:
    """How the patches were grouped into hoopings. ``spacing_mm`` only in free mode; the
    ``fewest_hoopings*`` and ``conflicts_exact`` only in garment mode (hoopings and order
    planned for the fewest frame conflicts first: ``grouping.conflict_plan``)."""

    method: str
    status: str
    optimal: bool
    mip_gap: float | None
    hoopings: int
    hoop_types: int
    hoopings_lower_bound: int
    first_fit_decreasing_hoopings: int
    candidates: int
    time_limit_s: float | None
    note: str
    spacing_mm: float | None = None
    fewest_hoopings: int | None = None           # garment: the set cover's count
    fewest_hoopings_conflicts: int | None = None  # the frame conflicts that grouping leaves
    conflicts_exact: bool = False                 # the plan's conflicts proven fewest

    def as_dict(self) -> dict:
        out = {"method": self.method, "status": self.status, "optimal": self.optimal,
               "mip_gap": self.mip_gap, "hoopings": self.hoopings, "hoop_types": self.hoop_types,
               "hoopings_lower_bound": self.hoopings_lower_bound,
               "first_fit_decreasing_hoopings": self.first_fit_decreasing_hoopings,
               "candidates": self.candidates, "time_limit_s": self.time_limit_s,
               "note": self.note}
        if self.spacing_mm is not None:
            out["spacing_mm"] = self.spacing_mm
        if self.fewest_hoopings is not None:
            out.update(fewest_hoopings=self.fewest_hoopings,
                       fewest_hoopings_conflicts=self.fewest_hoopings_conflicts,
                       conflicts_exact=self.conflicts_exact)
        return out


@dataclass(frozen=True)
class Conflict:
    """A hoop frame landing on a patch stitched earlier (hoopings numbered from 1)."""

    hooping: int
    patch: str
    stitched_in_hooping: int


@dataclass(frozen=True)
class HoopingFiles:
    embroidery: str
    png: str
    svg: str
    template_a4: str | None = None       # garment mode: 1:1 printable templates (PDF)
    template_letter: str | None = None
    marks_dxf: str | None = None         # garment mode: the same marks as DXF (relaxed mm)


@dataclass(frozen=True)
class PlacedPatch:
    order: int
    id: str
    position_hoop_mm: tuple[float, float]
    centre_garment_mm: tuple[float, float]
    diameter_mm: float
    fill: float
    conductive: str | None

    def as_dict(self) -> dict:
        return {"order": self.order, "id": self.id,
                "position_hoop_mm": list(self.position_hoop_mm),
                "centre_garment_mm": list(self.centre_garment_mm),
                "diameter_mm": self.diameter_mm, "fill": self.fill, "conductive": self.conductive}


@dataclass(frozen=True)
class Thread:
    """One colour block of the hooping's machine file, in file order. ``jef``: for a JEF file,
    the palette thread the file stores for the block and the machine shows
    (``embroidery.jef_palette.jef_threads``); None for other formats."""

    role: str
    colour: str
    patches: tuple[str, ...]
    jef: JefThread | None = None

    def as_dict(self) -> dict:
        d = {"role": self.role, "colour": self.colour, "patches": list(self.patches)}
        if self.jef is not None:
            d["jef_thread"] = self.jef.as_dict()
        return d

    def sheet_name(self) -> str:
        """The thread as the sheet and the workshop steps name it: the design colour, and for a
        JEF the palette thread the machine shows."""
        return self.colour if self.jef is None else self.jef.sheet_text(self.colour)


@dataclass(frozen=True)
class HoopingDoc:
    """One hooping. The garment position (``centre_*_mm``, ``alignment_marks_garment_mm``) is
    None in free mode, where a hooping is its own piece of fabric."""

    number: int
    hoop: str
    field_mm: tuple[float, float]
    margin_mm: float
    frame_width_mm: float
    jef_code: int | None
    orientation_deg: int
    piece: str | None
    centre_stretched_mm: tuple[float, float] | None
    centre_garment_mm: tuple[float, float] | None
    alignment_marks_garment_mm: tuple | None
    files: HoopingFiles
    patches: tuple[PlacedPatch, ...]
    threads: tuple[Thread, ...]
    stitches: int
    trims: int
    jumps: int
    colour_changes: int
    thread_length_m: float
    time_min: float
    gap_crossings: int = 0          # thread laid over unstitched fabric (the stitch audit)
    gap_crossing_mm: float = 0.0
    hoop_reason: str = ""           # why this hoop, in plain words (``hoop_reason``)
    small_pieces: int = 0           # pieces under stitches.SMALL_PIECE_AREA_MM2, sewn but warned

    def as_dict(self) -> dict:
        d = {"number": self.number, "hoop": self.hoop, "field_mm": list(self.field_mm),
             "margin_mm": self.margin_mm, "frame_width_mm": self.frame_width_mm,
             "jef_code": self.jef_code, "orientation_deg": self.orientation_deg,
             "piece": self.piece, "hoop_reason": self.hoop_reason}
        if self.piece is not None:
            d.update(centre_stretched_mm=list(self.centre_stretched_mm),
                     centre_garment_mm=list(self.centre_garment_mm),
                     alignment_marks_garment_mm=[list(m) for m in self.alignment_marks_garment_mm])
        d["files"] = asdict(self.files)
        d["patches"] = [p.as_dict() for p in self.patches]
        d["threads"] = [t.as_dict() for t in self.threads]
        d.update(stitches=self.stitches, trims=self.trims, jumps=self.jumps,
                 colour_changes=self.colour_changes, thread_length_m=self.thread_length_m,
                 time_min=self.time_min, gap_crossings=self.gap_crossings,
                 gap_crossing_mm=self.gap_crossing_mm, small_pieces=self.small_pieces)
        return d


@dataclass(frozen=True)
class Totals:
    hoopings: int
    patches: int
    stitches: int
    time_min: float


@dataclass(frozen=True)
class FabricationDoc:
    """Everything fabrication.json holds; ``overview_png`` / ``overview_svg`` name the
    overview figures, ``limits`` the caveats of the estimates."""

    generator: str
    version: str
    design: DesignFile
    mode: str
    machine: MachineInfo
    embroidery_format: str
    stretch: StretchInfo
    grouping: GroupingInfo
    order_exact: bool
    conflicts: tuple[Conflict, ...]
    hoopings: tuple[HoopingDoc, ...]
    totals: Totals
    overview_png: str
    overview_svg: str
    limits: tuple[str, ...]

    def as_dict(self) -> dict:
        return {
            "schema": SCHEMA, "generator": self.generator, "version": self.version,
            "design": asdict(self.design), "mode": self.mode,
            "machine": asdict(self.machine), "format": self.embroidery_format,
            "stretch": self.stretch.as_dict(), "grouping": self.grouping.as_dict(),
            "order": {"exact": self.order_exact,
                      "conflicts": [asdict(c) for c in self.conflicts]},
            "hoopings": [h.as_dict() for h in self.hoopings],
            "totals": asdict(self.totals),
            "files": {"overview_png": self.overview_png, "overview_svg": self.overview_svg},
            "limits": list(self.limits),
        }
