"""Reading, validating and writing design files (version 1, docs/design-file.md).

Every problem raises ``InvalidInputError`` whose message names the file and the JSON path of
the bad value, e.g. ``design file 'a.json': patches[3].fill: 1.4 is outside (0, 1]``.

The written form is canonical: the documented key order, two-space indent, a coordinate pair
per line, floats rounded to 6 decimals (1e-6 mm) and printed as Python's shortest repr, a final
newline. The same design therefore always gives the same bytes, and ``save_design`` validates
what it writes, so a saved file always loads.
"""
from __future__ import annotations

import json
import math
import os

import numpy as np

from stitchswitch.errors import InvalidInputError
from stitchswitch.files.atomic import atomic_write_text
from stitchswitch.files.textio import read_text
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
           "validate_design", "machine_hoops", "machine_names"]

DECIMALS = 6
TOL_MM = 1e-6          # geometric tolerance of the validator: the rounding of the file


def machine_hoops(name: str):
    """The hoops of a machine of the built-in catalogue (``layout.embroidery.machines``); KeyError if
    there is no such machine."""
    return _machine_table()[name]


def machine_names() -> tuple[str, ...]:
    return tuple(_machine_table())


def _machine_table() -> dict:
    try:
        from stitchswitch.layout.embroidery.machines import builtin_catalogue
    except ImportError:                       # no catalogue: the 550E's hoops
        from stitchswitch.layout.embroidery.hoops import JANOME_550E_HOOPS
        return {"janome-550e": JANOME_550E_HOOPS}
    return {m.name: m.hoops for m in builtin_catalogue().machines}


class _Invalid(Exception):
    def __init__(self, path: str, message: str):
        super().__init__(f"{path}: {message}")


# --- reading ------------------------------------------------------------------------------

def load_design(path) -> Design:
    """Read and validate a design file; the material it names is loaded once to check it."""
    where = f"design file {os.fspath(path)!r}"
    text = read_text(path, where)
    try:
        obj = json.loads(text, object_pairs_hook=_no_duplicates, parse_constant=_no_constant)
    except json.JSONDecodeError as exc:
        raise InvalidInputError(f"{where}: not valid JSON ({exc.msg} at line {exc.lineno}, "
                                f"column {exc.colno})") from None
    except _Invalid as exc:
        raise InvalidInputError(f"{where}: {exc}") from None
    design = design_from_dict(obj, where)
    design = Design(design.version, design.pieces, design.patches, design.material,
                    design.machine, path=os.fspath(path))
    try:
        design.material_object()
    except InvalidInputError as exc:
        raise InvalidInputError(f"{where}: {exc}") from None
    return design


def _no_duplicates(pairs):
    out = {}
    for key, value in pairs:
        if key in out:
            raise _Invalid("$", f"duplicate key {key!r}")
        out[key] = value
    return out


def _no_constant(name):
    raise _Invalid("$", f"{name} is not a finite number")


def design_from_dict(obj, source: str = "design") -> Design:
    """Validate a parsed design file (dict) and build the ``Design``; errors start with
    ``source`` and name the JSON path."""
    try:
        return _design(obj)
    except _Invalid as exc:
        raise InvalidInputError(f"{source}: {exc}") from None


def validate_design(design: Design, source: str = "design") -> Design:
    """Check an in-memory design by the file's rules (e.g. after placing patches)."""
    checked = design_from_dict(design_to_dict(design), source)
    return Design(checked.version, checked.pieces, checked.patches, checked.material,
                  checked.machine, design.path)


def _design(obj) -> Design:
    if not isinstance(obj, dict):
        raise _Invalid("$", f"a design must be a JSON object, got {_kind(obj)}")
    if "version" not in obj:
        raise _Invalid("version", "missing (this stitchswitch reads version 1)")
    version = obj["version"]
    if isinstance(version, bool) or not isinstance(version, int) or version != VERSION:
        raise _Invalid("version", f"{version!r} is not a supported design file version "
                                  f"(this stitchswitch reads version {VERSION})")
    _keys(obj, "$", required=("version", "pieces", "patches"), optional=("material", "machine"))
    pieces = tuple(_piece(p, f"pieces[{i}]") for i, p in enumerate(_list(obj["pieces"], "pieces")))
    names = {}
    for i, p in enumerate(pieces):
        if p.name in names:
            raise _Invalid(f"pieces[{i}].name", f"{p.name!r} is already the name of "
                                                f"pieces[{names[p.name]}]")
        names[p.name] = i
    patches = tuple(_patch(p, f"patches[{i}]", names)
                    for i, p in enumerate(_list(obj["patches"], "patches")))
    ids = {}
    for i, p in enumerate(patches):
        if p.id in ids:
            raise _Invalid(f"patches[{i}].id",
                           f"{p.id!r} is already the id of patches[{ids[p.id]}]")
        ids[p.id] = i
    material = _material(obj.get("material", {"name": "default"}), "material")
    machine = _machine(obj.get("machine", {"name": "janome-550e", "hoop": None}), "machine")
    return Design(version, pieces, patches, material, machine)


def _piece(obj, path) -> PieceSpec:
    _keys(obj, path, required=("name", "outline_mm"), optional=("size", "source"))
    name = _text(obj["name"], f"{path}.name", nonempty=True)
    size = _text(obj.get("size", ""), f"{path}.size")
    source = _text(obj.get("source", ""), f"{path}.source")
    ring = _points(obj["outline_mm"], f"{path}.outline_mm")
    if len(ring) > 3 and np.allclose(ring[0], ring[-1], rtol=0.0, atol=TOL_MM):
        ring = ring[:-1]                     # a repeated first point is accepted and dropped
    if len(ring) < 3:
        raise _Invalid(f"{path}.outline_mm", f"needs at least 3 distinct points, got {len(ring)}")
    if abs(_area(ring)) <= TOL_MM:
        raise _Invalid(f"{path}.outline_mm", "encloses no area")
    return PieceSpec(name, size, source, ring)


def _patch(obj, path, pieces: dict) -> PatchSpec:
    from stitchswitch.layout.embroidery.patch_geometry import DIAMETER_RANGE_MM, parse_selection

    _keys(obj, path, required=("id", "piece", "centre_mm", "diameter_mm", "fill"),
          optional=("composite", "outline_mm", "conductive", "threads", "state"))
    pid = _text(obj["id"], f"{path}.id", nonempty=True)
    piece = _text(obj["piece"], f"{path}.piece", nonempty=True)
    if piece not in pieces:
        raise _Invalid(f"{path}.piece", f"{piece!r} is not a piece of this design (pieces: "
                                        + (", ".join(pieces) or "none") + ")")
    centre = _point(obj["centre_mm"], f"{path}.centre_mm")
    lo, hi = DIAMETER_RANGE_MM
    d = _number(obj["diameter_mm"], f"{path}.diameter_mm")
    if not lo <= d <= hi:
        raise _Invalid(f"{path}.diameter_mm",
                       f"{obj['diameter_mm']!r} is outside [{lo:g}, {hi:g}] mm")
    fill = _fraction(obj["fill"], f"{path}.fill")
    composite = obj.get("composite")
    if composite is not None:
        composite = _composite(composite, f"{path}.composite", d)
    outline = obj.get("outline_mm")
    if outline is not None:
        outline = _outline(outline, f"{path}.outline_mm", d, composite, path)
    conductive = obj.get("conductive")
    if conductive is not None:
        conductive = _text(conductive, f"{path}.conductive", nonempty=True)
        try:
            parse_selection(conductive)
        except InvalidInputError as exc:
            raise _Invalid(f"{path}.conductive", str(exc)) from None
    threads = _threads(obj.get("threads", {}), f"{path}.threads")
    state = obj.get("state", "up")
    if state not in STATES:
        raise _Invalid(f"{path}.state", f"{state!r} is not one of " + ", ".join(map(repr, STATES)))
    return PatchSpec(pid, piece, centre, d, fill, composite, outline, conductive, threads, state)


def _composite(obj, path, d) -> CompositeSpec:
    _keys(obj, path, required=("core_diameter_mm", "core_fill"))
    core = _number(obj["core_diameter_mm"], f"{path}.core_diameter_mm")
    if not 0.0 < core < d:
        raise _Invalid(f"{path}.core_diameter_mm",
                       f"{obj['core_diameter_mm']!r} is outside (0, {d:g}) mm (the patch diameter)")
    return CompositeSpec(core, _fraction(obj["core_fill"], f"{path}.core_fill"))


def _outline(obj, path, d, composite, patch_path) -> np.ndarray:
    import shapely

    ring = _points(obj, path)
    if composite is None:
        raise _Invalid(path, f"a custom outline needs {patch_path}.composite (the circular "
                             "functional core); add a composite or set outline_mm to null")
    if len(ring) < 3:
        raise _Invalid(path, f"needs at least 3 points, got {len(ring)}")
    dist = np.hypot(ring[:, 0], ring[:, 1])
    far = int(np.argmax(dist))
    if dist[far] > d / 2.0 + TOL_MM:
        raise _Invalid(f"{path}[{far}]", f"{ring[far].tolist()} lies {dist[far]:.6g} mm from the "
                                         f"centre, outside the patch radius {d / 2:g} mm")
    poly = shapely.Polygon(ring)
    if not poly.is_valid or poly.area <= TOL_MM:
        reason = shapely.is_valid_reason(poly) if not poly.is_valid else "no area"
        raise _Invalid(path, f"is not a simple polygon ({reason})")
    rc = composite.core_diameter_mm / 2.0
    origin = shapely.Point(0.0, 0.0)
    gap = poly.exterior.distance(origin)
    if not poly.contains(origin) or gap < rc - TOL_MM:
        raise _Invalid(path, f"the core disc (diameter {composite.core_diameter_mm:g} mm) is not "
                             f"inside the outline (closest outline point {gap:.6g} mm from the "
                             "centre)" if poly.contains(origin) else "does not contain the centre")
    return ring


def _threads(obj, path) -> Threads:
    _keys(obj, path, optional=("top", "conductive"))
    default = Threads()
    return Threads(_colour(obj.get("top", default.top), f"{path}.top"),
                   _colour(obj.get("conductive", default.conductive), f"{path}.conductive"))


def _colour(value, path) -> str:
    text = _text(value, path)
    ok = len(text) == 7 and text[0] == "#" and all(c in "0123456789abcdefABCDEF" for c in text[1:])
    if not ok:
        raise _Invalid(path, f"{value!r} is not a colour #rrggbb")
    return text.lower()


def _material(obj, path) -> MaterialRef:
    _keys(obj, path, optional=("name", "file"))
    if ("name" in obj) == ("file" in obj):
        raise _Invalid(path, "give exactly one of 'name' (a built-in material) or 'file'")
    if "file" in obj:
        return MaterialRef(name=None, file=_text(obj["file"], f"{path}.file", nonempty=True))
    name = _text(obj["name"], f"{path}.name", nonempty=True)
    if name != "default":
        raise _Invalid(f"{path}.name", f"{name!r} is not a built-in material (the built-in "
                                       "material is 'default'; use 'file' for your own)")
    return MaterialRef(name=name, file=None)


def _machine(obj, path) -> MachineSpec:
    _keys(obj, path, optional=("name", "hoop"))
    name = _text(obj.get("name", "janome-550e"), f"{path}.name", nonempty=True)
    try:
        hoops = machine_hoops(name)
    except KeyError:
        raise _Invalid(f"{path}.name", f"unknown machine {name!r} (machines: "
                                       + ", ".join(machine_names()) + ")") from None
    hoop = obj.get("hoop")
    if hoop is not None:
        text = _text(hoop, f"{path}.hoop", nonempty=True)
        match = [h for h in hoops if h.name.lower() == text.lower()]
        if not match:
            raise _Invalid(f"{path}.hoop", f"{hoop!r} is not a hoop of the {name} (hoops: "
                                           + ", ".join(h.name for h in hoops) + ")")
        hoop = match[0].name
    return MachineSpec(name, hoop)


# --- small typed readers ------------------------------------------------------------------

def _kind(value) -> str:
    return {dict: "an object", list: "an array", str: "a string", bool: "a boolean",
            type(None): "null"}.get(type(value), "a number")


def _keys(obj, path, required=(), optional=()):
    if not isinstance(obj, dict):
        raise _Invalid(path, f"must be an object, got {_kind(obj)}")
    for key in required:
        if key not in obj:
            raise _Invalid(f"{path}.{key}" if path != "$" else key, "missing")
    unknown = [k for k in obj if k not in required and k not in optional]
    if unknown:
        where = f"{path}.{unknown[0]}" if path != "$" else unknown[0]
        raise _Invalid(where, "unknown key (allowed: " + ", ".join((*required, *optional)) + ")")


def _list(value, path) -> list:
    if not isinstance(value, list):
        raise _Invalid(path, f"must be an array, got {_kind(value)}")
    return value


def _text(value, path, nonempty=False) -> str:
    if not isinstance(value, str):
        raise _Invalid(path, f"must be a string, got {_kind(value)}")
    if nonempty and not value.strip():
        raise _Invalid(path, "must not be empty")
    return value


def _number(value, path) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise _Invalid(path, f"{value!r} is not a number")
    if not math.isfinite(value):
        raise _Invalid(path, f"{value!r} is not a finite number")
    return float(value)


def _fraction(value, path) -> float:
    v = _number(value, path)
    if not 0.0 < v <= 1.0:
        raise _Invalid(path, f"{value!r} is outside (0, 1]")
    return v


def _point(value, path) -> tuple[float, float]:
    if not isinstance(value, list) or len(value) != 2:
        raise _Invalid(path, f"must be a pair [x, y], got {json.dumps(value)[:60]}")
    return (_number(value[0], f"{path}[0]"), _number(value[1], f"{path}[1]"))


def _points(value, path) -> np.ndarray:
    pts = [_point(p, f"{path}[{i}]") for i, p in enumerate(_list(value, path))]
    return np.asarray(pts, dtype=float).reshape(-1, 2)


def _area(ring: np.ndarray) -> float:
    x, y = ring[:, 0], ring[:, 1]
    return 0.5 * float(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1)))


# --- writing ------------------------------------------------------------------------------

def _r(x: float) -> float:
    v = round(float(x), DECIMALS)
    return 0.0 if v == 0 else v       # no "-0.0"


def _pts(arr) -> list:
    return [[_r(x), _r(y)] for x, y in np.asarray(arr, dtype=float)]


def design_to_dict(design: Design) -> dict:
    """The file's JSON object (documented key order, floats rounded to 1e-6)."""
    return {
        "version": design.version,
        "pieces": [{"name": p.name, "size": p.size, "source": p.source,
                    "outline_mm": _pts(p.outline_mm)} for p in design.pieces],
        "patches": [_patch_dict(p) for p in design.patches],
        "material": ({"file": design.material.file} if design.material.file is not None
                     else {"name": design.material.name}),
        "machine": {"name": design.machine.name, "hoop": design.machine.hoop},
    }


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
