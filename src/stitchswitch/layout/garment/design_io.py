"""Reading, validating and writing design files (version 1, docs/design-file.md).

Every problem raises ``InvalidInputError`` whose message names the file and the JSON path of
the bad value (``files.json_checks``), e.g. ``design file 'a.json': $.patches[3].fill: 1.4 is
outside (0, 1]``. The machine and its hoop are checked against the built-in catalogue
(``layout.embroidery.machines``).

The written form is canonical: the documented key order, two-space indent, a coordinate pair
per line, floats rounded to 6 decimals (1e-6 mm) and printed as Python's shortest repr, a final
newline. The same design therefore always gives the same bytes, and ``save_design`` validates
what it writes, so a saved file always loads.
"""
from __future__ import annotations

import json
import os
from dataclasses import replace

import numpy as np

from stitchswitch.errors import InvalidInputError
from stitchswitch.files import json_checks as jc
from stitchswitch.files.atomic import atomic_write_text
from stitchswitch.files.json_checks import child
from stitchswitch.layout.embroidery.machines import DEFAULT_MACHINE, builtin_catalogue
from stitchswitch.layout.embroidery.tessellation import polygon_area
from stitchswitch.layout.garment.design import (
    STATES,
    VERSION,
    CompositeSpec,
    Design,
    MachineSpec,
    MaterialRef,
    PatchSpec,
    PieceSpec,
    Threads,
)

__all__ = ["load_design", "save_design", "design_from_dict", "design_to_dict", "dumps_design",
           "validate_design"]

DECIMALS = 6
TOL_MM = 1e-6          # geometric tolerance of the validator: the rounding of the file
MAX_BLANK_MARGIN_MM = 1000.0   # an uncut blank reaching a metre past its piece is a typo


# --- reading ------------------------------------------------------------------------------

def load_design(path) -> Design:
    """Read and validate a design file; the material it names is loaded once to check it."""
    where = f"design file {os.fspath(path)!r}"
    design = design_from_dict(jc.load_file(path, where), where)
    design = replace(design, path=os.fspath(path))
    try:
        design.material_object()
    except InvalidInputError as exc:
        raise InvalidInputError(f"{where}: {exc}") from None
    return design


def design_from_dict(obj, source: str = "design") -> Design:
    """Validate a parsed design file (dict) and build the ``Design``; errors start with
    ``source`` and name the JSON path."""
    with jc.reporting(source):
        return _design(obj, jc.ROOT)


def validate_design(design: Design, source: str = "design") -> Design:
    """Check an in-memory design by the file's rules (e.g. after placing patches)."""
    checked = design_from_dict(design_to_dict(design), source)
    return replace(checked, path=design.path)


def _design(obj, path) -> Design:
    if not isinstance(obj, dict):
        jc.obj(obj, path, what="a design")
    version_path = child(path, "version")
    if "version" not in obj:
        jc.fail(version_path, f"missing (this stitchswitch reads version {VERSION})")
    version = obj["version"]
    if isinstance(version, bool) or not isinstance(version, int) or version != VERSION:
        jc.fail(version_path, f"{jc.show(version)} is not a supported design file version "
                              f"(this stitchswitch reads version {VERSION})")
    jc.obj(obj, path, required=("version", "pieces", "patches"),
           optional=("material", "machine", "blank_margin_mm"))
    pieces_path, patches_path = child(path, "pieces"), child(path, "patches")
    pieces = tuple(jc.items(obj["pieces"], pieces_path, _piece))
    jc.unique([p.name for p in pieces], pieces_path, "name")
    names = {p.name: i for i, p in enumerate(pieces)}
    patches = tuple(jc.items(obj["patches"], patches_path,
                             lambda p, where: _patch(p, where, names)))
    jc.unique([p.id for p in patches], patches_path, "id")
    material = _material(obj.get("material", {"name": "default"}), child(path, "material"))
    machine = _machine(obj.get("machine", {}), child(path, "machine"))
    blank = jc.number(obj.get("blank_margin_mm", 0.0), child(path, "blank_margin_mm"), low=0.0,
                      high=MAX_BLANK_MARGIN_MM, unit="mm")
    return Design(version, pieces, patches, material, machine, blank_margin_mm=blank)


def _piece(obj, path) -> PieceSpec:
    jc.obj(obj, path, required=("name", "outline_mm"), optional=("size", "source"))
    name = jc.text(obj["name"], child(path, "name"), nonempty=True, printable=True)
    size = jc.text(obj.get("size", ""), child(path, "size"), printable=True)
    source = jc.text(obj.get("source", ""), child(path, "source"))
    outline_path = child(path, "outline_mm")
    ring = _points(obj["outline_mm"], outline_path)
    if len(ring) > 3 and np.allclose(ring[0], ring[-1], rtol=0.0, atol=TOL_MM):
        ring = ring[:-1]                     # a repeated first point is accepted and dropped
    if len(ring) < 3:
        jc.fail(outline_path, f"needs at least 3 distinct points, got {len(ring)}")
    if abs(polygon_area(ring)) <= TOL_MM:
        jc.fail(outline_path, "encloses no area")
    return PieceSpec(name, size, source, ring)


def _patch(obj, path, pieces: dict) -> PatchSpec:
    from stitchswitch.layout.embroidery.patch_geometry import DIAMETER_RANGE_MM, parse_selection

    jc.obj(obj, path, required=("id", "piece", "centre_mm", "diameter_mm", "fill"),
           optional=("composite", "outline_mm", "conductive", "threads", "state"))
    pid = jc.text(obj["id"], child(path, "id"), nonempty=True, printable=True)
    piece = jc.text(obj["piece"], child(path, "piece"), nonempty=True)
    if piece not in pieces:
        jc.fail(child(path, "piece"), f"{jc.show(piece)} is not a piece of this design "
                                      f"(pieces: {jc.show_all(pieces) or 'none'})")
    centre = _point(obj["centre_mm"], child(path, "centre_mm"))
    lo, hi = DIAMETER_RANGE_MM
    d = jc.number(obj["diameter_mm"], child(path, "diameter_mm"), low=lo, high=hi, unit="mm")
    fill = _fraction(obj["fill"], child(path, "fill"))
    composite = obj.get("composite")
    if composite is not None:
        composite = _composite(composite, child(path, "composite"), d)
    outline = obj.get("outline_mm")
    if outline is not None:
        outline = _outline(outline, child(path, "outline_mm"), d, composite,
                           child(path, "composite"))
    conductive = obj.get("conductive")
    if conductive is not None:
        conductive = jc.text(conductive, child(path, "conductive"), nonempty=True)
        with jc.at(child(path, "conductive")):
            parse_selection(conductive)
    threads = _threads(obj.get("threads", {}), child(path, "threads"))
    state = jc.choice(obj.get("state", "up"), child(path, "state"), STATES)
    return PatchSpec(pid, piece, centre, d, fill, composite, outline, conductive, threads, state)


def _composite(obj, path, d) -> CompositeSpec:
    jc.obj(obj, path, required=("core_diameter_mm", "core_fill"))
    core = jc.number(obj["core_diameter_mm"], child(path, "core_diameter_mm"), low=0.0, high=d,
                     low_open=True, high_open=True, unit="mm", note="the patch diameter")
    return CompositeSpec(core, _fraction(obj["core_fill"], child(path, "core_fill")))


def _outline(obj, path, d, composite, composite_path) -> np.ndarray:
    import shapely

    ring = _points(obj, path)
    if composite is None:
        jc.fail(path, f"a custom outline needs {composite_path} (the circular functional "
                      "core); add a composite or set outline_mm to null")
    if len(ring) < 3:
        jc.fail(path, f"needs at least 3 points, got {len(ring)}")
    dist = np.hypot(ring[:, 0], ring[:, 1])
    far = int(np.argmax(dist))
    if dist[far] > d / 2.0 + TOL_MM:
        jc.fail(child(path, far), f"{ring[far].tolist()} lies {dist[far]:.6g} mm from the "
                                  f"centre, outside the patch radius {d / 2:g} mm")
    poly = shapely.Polygon(ring)
    if not poly.is_valid or poly.area <= TOL_MM:
        reason = shapely.is_valid_reason(poly) if not poly.is_valid else "no area"
        jc.fail(path, f"is not a simple polygon ({reason})")
    rc = composite.core_diameter_mm / 2.0
    origin = shapely.Point(0.0, 0.0)
    gap = poly.exterior.distance(origin)
    if not poly.contains(origin) or gap < rc - TOL_MM:
        jc.fail(path, f"the core disc (diameter {composite.core_diameter_mm:g} mm) is not "
                      f"inside the outline (closest outline point {gap:.6g} mm from the "
                      "centre)" if poly.contains(origin) else "does not contain the centre")
    return ring


def _threads(obj, path) -> Threads:
    jc.obj(obj, path, optional=("top", "conductive"))
    default = Threads()
    return Threads(_colour(obj.get("top", default.top), child(path, "top")),
                   _colour(obj.get("conductive", default.conductive), child(path, "conductive")))


def _colour(value, path) -> str:
    text = jc.text(value, path)
    ok = len(text) == 7 and text[0] == "#" and all(c in "0123456789abcdefABCDEF" for c in text[1:])
    if not ok:
        jc.fail(path, f"{jc.show(value)} is not a colour #rrggbb")
    return text.lower()


def _material(obj, path) -> MaterialRef:
    jc.obj(obj, path, optional=("name", "file"))
    if ("name" in obj) == ("file" in obj):
        jc.fail(path, "give exactly one of 'name' (a built-in material) or 'file'")
    if "file" in obj:
        return MaterialRef(name=None, file=jc.text(obj["file"], child(path, "file"),
                                                   nonempty=True))
    name = jc.text(obj["name"], child(path, "name"), nonempty=True)
    if name != "default":
        jc.fail(child(path, "name"), f"{jc.show(name)} is not a built-in material (the built-in "
                                     "material is 'default'; use 'file' for your own)")
    return MaterialRef(name=name, file=None)


def _machine(obj, path) -> MachineSpec:
    jc.obj(obj, path, optional=("name", "hoop"))
    name_path, hoop_path = child(path, "name"), child(path, "hoop")
    name = jc.text(obj.get("name", DEFAULT_MACHINE), name_path, nonempty=True)
    with jc.at(name_path):
        machine = builtin_catalogue().machine(name)
    hoop = obj.get("hoop")
    if hoop is not None:
        with jc.at(hoop_path):
            hoop = machine.hoop(jc.text(hoop, hoop_path, nonempty=True)).name
    return MachineSpec(machine.name, hoop)


# --- small typed readers ------------------------------------------------------------------

def _fraction(value, path) -> float:
    return jc.number(value, path, low=0.0, high=1.0, low_open=True)


def _point(value, path) -> tuple[float, float]:
    if not isinstance(value, list) or len(value) != 2:
        jc.fail(path, f"must be a pair [x, y], got {jc.show(value)}")
    return (jc.number(value[0], child(path, 0)), jc.number(value[1], child(path, 1)))


def _points(value, path) -> np.ndarray:
    pts = jc.items(value, path, _point)
    return np.asarray(pts, dtype=float).reshape(-1, 2)


# --- writing ------------------------------------------------------------------------------

def _r(x: float) -> float:
    v = round(float(x), DECIMALS)
    return 0.0 if v == 0 else v       # no "-0.0"


def _pts(arr) -> list:
    return [[_r(x), _r(y)] for x, y in np.asarray(arr, dtype=float)]


def design_to_dict(design: Design) -> dict:
    """The file's JSON object (documented key order, floats rounded to 1e-6)."""
    out = {
        "version": design.version,
        "pieces": [{"name": p.name, "size": p.size, "source": p.source,
                    "outline_mm": _pts(p.outline_mm)} for p in design.pieces],
        "patches": [_patch_dict(p) for p in design.patches],
        "material": ({"file": design.material.file} if design.material.file is not None
                     else {"name": design.material.name}),
        "machine": {"name": design.machine.name, "hoop": design.machine.hoop},
    }
    if design.blank_margin_mm:                # written only when set: old files keep their bytes
        out["blank_margin_mm"] = _r(design.blank_margin_mm)
    return out


def _patch_dict(p: PatchSpec) -> dict:
    composite = None if p.composite is None else {
        "core_diameter_mm": _r(p.composite.core_diameter_mm),
        "core_fill": _r(p.composite.core_fill)}
    return {"id": p.id, "piece": p.piece, "centre_mm": [_r(p.centre_mm[0]), _r(p.centre_mm[1])],
            "diameter_mm": _r(p.diameter_mm), "fill": _r(p.fill), "composite": composite,
            "outline_mm": None if p.outline_mm is None else _pts(p.outline_mm),
            "conductive": p.conductive,
            "threads": {"top": p.threads.top, "conductive": p.threads.conductive},
            "state": p.state}


def dumps_design(design: Design) -> str:
    """The canonical text of a design (validated)."""
    obj = design_to_dict(design)
    design_from_dict(obj, "design to write")
    return _emit(obj, 0) + "\n"


def save_design(design: Design, path) -> None:
    """Validate and write ``design`` to ``path`` atomically, in canonical form."""
    atomic_write_text(path, dumps_design(design))


def _is_num(v) -> bool:
    return isinstance(v, (int, float)) and not isinstance(v, bool)


def _emit(v, level: int) -> str:
    pad, inner = "  " * level, "  " * (level + 1)
    if isinstance(v, dict):
        if not v:
            return "{}"
        items = [f"{inner}{json.dumps(k)}: {_emit(x, level + 1)}" for k, x in v.items()]
        return "{\n" + ",\n".join(items) + "\n" + pad + "}"
    if isinstance(v, list):
        if not v:
            return "[]"
        if all(_is_num(x) for x in v):
            return "[" + ", ".join(_emit(x, level) for x in v) + "]"
        return "[\n" + ",\n".join(inner + _emit(x, level + 1) for x in v) + "\n" + pad + "]"
    if isinstance(v, float):
        return repr(v)
    return json.dumps(v, ensure_ascii=False)
