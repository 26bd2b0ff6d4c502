"""Plain DXF (R12 to R2018) geometry: flatten curves to polylines and gather the closed outlines.

Every closed contour in model space (INSERTs expanded with their transforms) becomes one piece;
open curves are joined end to end by ``chain.chain_loops`` (docs/dxf.md). Coordinates here are
in drawing units; the caller scales them to mm.

The entities come from the user's file, so each is checked before ezdxf flattens it: a
non-finite or far-out coordinate or radius (beyond ``limit``, which the reader sets to
``MAX_EXTENT_MM`` in drawing units) is refused, since flattening it could take without end;
what ezdxf still cannot flatten (a spline with the wrong number of knots, a vertex without a
location) is reported as malformed geometry of that entity. Block references are expanded
here, not by ezdxf's recursive decomposition, so that a block that inserts itself, nesting
deeper than ``MAX_NESTING`` or more than ``MAX_ENTITIES`` entities are errors, not a
RecursionError or a run without end.
"""
from __future__ import annotations

import math

import numpy as np

from stitchswitch.errors import InvalidInputError
from stitchswitch.files.shown import clip

MAX_NESTING = 16
MAX_ENTITIES = 1_000_000

#: What ezdxf raises on an entity it cannot flatten (its own DXFError included).
GEOMETRY_ERRORS = (ArithmeticError, LookupError, TypeError, ValueError, AttributeError,
                   RecursionError)


def entity_name(entity) -> str:
    handle = entity.dxf.get("handle")
    return f"{entity.dxftype()} {handle}" if handle else entity.dxftype()


def check_point(p, limit: float, entity, what: str, where: str) -> None:
    if not all(math.isfinite(c) and abs(c) <= limit for c in p):
        raise InvalidInputError(f"{where}: {entity_name(entity)}: {what} "
                                f"({', '.join(f'{c:.4g}' for c in p)}) is not finite or lies "
                                f"beyond {limit:.4g} drawing units")


def _check_length(x, limit: float, entity, what: str, where: str) -> None:
    if not (math.isfinite(x) and 0.0 < abs(x) <= limit):
        raise InvalidInputError(f"{where}: {entity_name(entity)}: {what} {x:.4g} is not in "
                                f"(0, {limit:.4g}] drawing units")


def _check_curve(entity, kind: str, limit: float, where: str) -> None:
    """Refuse what would make ezdxf's flattening run away: a non-finite or huge coordinate."""
    if kind in ("ARC", "CIRCLE"):
        check_point(entity.dxf.center, limit, entity, "centre", where)
        _check_length(entity.dxf.radius, limit, entity, "radius", where)
    elif kind == "ELLIPSE":
        check_point(entity.dxf.center, limit, entity, "centre", where)
        _check_length(float(np.linalg.norm(entity.dxf.major_axis)), limit, entity,
                      "major axis", where)
        _check_length(entity.dxf.ratio, 1.0, entity, "axis ratio", where)
        for name in ("start_param", "end_param"):
            if not math.isfinite(entity.dxf.get(name, 0.0)):
                raise InvalidInputError(f"{where}: {entity_name(entity)}: {name} is not finite")
    elif kind == "SPLINE":
        for p in (*entity.control_points, *entity.fit_points):
            check_point(p, limit, entity, "control point", where)
        if not all(math.isfinite(k) for k in entity.knots):
            raise InvalidInputError(f"{where}: {entity_name(entity)}: a knot is not finite")


def flatten(entity, tolerance: float, limit: float, where: str) -> np.ndarray | None:
    """The entity as a (k, 2) vertex array, vertices on the curve, chords within `tolerance`;
    None for what is not an outline (texts, points, meshes). Bad geometry raises
    ``InvalidInputError`` naming ``where`` and the entity."""
    try:
        pts = _vertices(entity, tolerance, limit, where)
    except InvalidInputError:
        raise
    except GEOMETRY_ERRORS as exc:
        raise InvalidInputError(f"{where}: {entity_name(entity)}: malformed geometry "
                                f"({clip(str(exc), 80)})") from None
    if pts is None:
        return None
    pts = np.array([(v[0], v[1]) for v in pts], dtype=float)
    if not (np.all(np.isfinite(pts)) and np.all(np.abs(pts) <= limit)):
        bad = pts[np.argmax(~np.isfinite(pts).all(axis=1) | (np.abs(pts) > limit).any(axis=1))]
        check_point(bad, limit, entity, "vertex", where)
    keep = np.r_[True, np.any(np.diff(pts, axis=0) != 0.0, axis=1)]   # drop repeated vertices
    pts = pts[keep]
    return pts if len(pts) >= 2 else None


def _vertices(entity, tolerance: float, limit: float, where: str):
    kind = entity.dxftype()
    _check_curve(entity, kind, limit, where)
    if kind == "LINE":
        return [entity.dxf.start, entity.dxf.end]
    if kind in ("ARC", "CIRCLE"):
        return list(entity.flattening(sagitta=tolerance))
    if kind in ("ELLIPSE", "SPLINE"):
        return list(entity.flattening(distance=tolerance))
    if kind == "LWPOLYLINE" or (kind == "POLYLINE" and (entity.is_2d_polyline
                                                          or entity.is_3d_polyline)):
        parts = [p for e in entity.virtual_entities()
                 if (p := flatten(e, tolerance, limit, where)) is not None]
        if not parts:
            return None
        return np.vstack([parts[0]] + [p[1:] for p in parts[1:]])
    return None


def block_entities(insert, where: str) -> list:
    """The entities an INSERT places (its transform applied; a multi-insert's copies as
    INSERTs), refusing a missing block and more than ``MAX_ENTITIES`` copies."""
    if insert.block() is None:
        raise InvalidInputError(f"{where}: {entity_name(insert)} refers to a missing block "
                                f"{clip(str(insert.dxf.get('name')))!r}")
    if insert.mcount > 1:
        if insert.mcount > MAX_ENTITIES:
            raise InvalidInputError(f"{where}: {entity_name(insert)}: an array of "
                                    f"{insert.mcount} copies (more than {MAX_ENTITIES})")
        return list(insert.multi_insert())
    try:
        return [*insert.attribs, *insert.virtual_entities()]
    except GEOMETRY_ERRORS as exc:
        raise InvalidInputError(f"{where}: {entity_name(insert)}: malformed block reference "
                                f"({clip(str(exc), 80)})") from None


def expanded(entities, where: str):
    """The entities with block references and other compound entities (dimensions, leaders)
    replaced by what they draw, depth first in file order."""
    from ezdxf.entities import Insert
    from ezdxf.protocols import SupportsVirtualEntities, virtual_entities

    stack = [(e, ()) for e in reversed(list(entities))]
    count = 0
    while stack:
        entity, blocks = stack.pop()
        count += 1
        if count > MAX_ENTITIES:
            raise InvalidInputError(f"{where}: more than {MAX_ENTITIES} entities once the blocks "
                                    "are expanded")
        if isinstance(entity, Insert):
            name = entity.dxf.get("name")
            if name in blocks:
                raise InvalidInputError(f"{where}: block {clip(str(name))!r} inserts itself "
                                        f"(through {' > '.join(map(str, blocks))})")
            if len(blocks) >= MAX_NESTING:
                raise InvalidInputError(f"{where}: blocks nested deeper than {MAX_NESTING} levels")
            children = block_entities(entity, where)
            inner = blocks if entity.mcount > 1 else blocks + (name,)
        elif isinstance(entity, SupportsVirtualEntities):
            try:
                children = list(virtual_entities(entity))
            except GEOMETRY_ERRORS as exc:
                raise InvalidInputError(f"{where}: {entity_name(entity)}: malformed geometry "
                                        f"({clip(str(exc), 80)})") from None
            inner = blocks
        else:
            yield entity
            continue
        stack.extend((c, inner) for c in reversed(children))


def read_generic(doc, tolerance: float, snap: float, unit: str, scale: float, source: str,
                 limit: float):
    """(name, size, ring, annotations) for every closed contour in model space."""
    from stitchswitch.layout.garment.dxf.chain import chain_loops, curve_length, local_tolerance

    closed, open_ = [], []
    for e in expanded(doc.modelspace(), source):
        pts = flatten(e, tolerance, limit, source)
        if pts is None:
            continue
        name = f"{e.dxftype()}_{e.dxf.get('handle') or len(closed) + len(open_)}"
        gap = np.hypot(*(pts[-1] - pts[0]))
        is_closed = len(pts) >= 4 and gap <= local_tolerance(snap, curve_length(pts))
        (closed if is_closed else open_).append((name, pts))
    rings = [(name, pts[:-1]) for name, pts in closed]
    if open_:
        where = f"{source}: open curves {', '.join(n for n, _ in open_[:5])}"
        for k, ring in enumerate(chain_loops([p for _, p in open_], snap, where, unit, scale)):
            rings.append((f"CHAIN_{k + 1}", ring))
    if not rings:
        raise InvalidInputError(f"{source}: no closed outline found in model space")
    return [(name, "", ring, {}) for name, ring in rings]
