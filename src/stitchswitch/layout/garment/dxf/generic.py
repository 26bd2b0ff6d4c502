"""Plain DXF (R12 to R2018) geometry: flatten curves to polylines and chain them into closed outlines.

Every closed contour in model space (INSERTs expanded with their transforms) becomes one piece;
open curves are joined end to end when their ends lie within the snap tolerance (docs/dxf.md).
Coordinates here are in drawing units; the caller scales them to mm.
"""
from __future__ import annotations

import numpy as np
from ezdxf import disassemble

from stitchswitch.errors import InvalidInputError


def flatten(entity, tolerance: float) -> np.ndarray | None:
    """The entity as a (k, 2) vertex array, vertices on the curve, chords within `tolerance`."""
    kind = entity.dxftype()
    if kind == "LINE":
        pts = [entity.dxf.start, entity.dxf.end]
    elif kind in ("ARC", "CIRCLE"):
        pts = list(entity.flattening(sagitta=tolerance))
    elif kind in ("ELLIPSE", "SPLINE"):
        pts = list(entity.flattening(distance=tolerance))
    elif kind == "LWPOLYLINE" or (kind == "POLYLINE" and (entity.is_2d_polyline
                                                            or entity.is_3d_polyline)):
        parts = [p for e in entity.virtual_entities() if (p := flatten(e, tolerance)) is not None]
        if not parts:
            return None
        pts = np.vstack([parts[0]] + [p[1:] for p in parts[1:]])
    else:
        return None                                     # texts, points, meshes: not outlines
    pts = np.array([(v[0], v[1]) for v in pts], dtype=float)
    keep = np.r_[True, np.any(np.diff(pts, axis=0) != 0.0, axis=1)]   # drop repeated vertices
    pts = pts[keep]
    return pts if len(pts) >= 2 else None


def chain_loops(fragments: list[np.ndarray], snap: float, where: str, unit: str,
                scale: float) -> list[np.ndarray]:
    """Join polylines end to end into closed rings (no repeated last point).

    Raises InvalidInputError naming `where` and the gap (converted to mm with `scale`) when a
    chain cannot be continued or closed within `snap`.
    """
    loops, rest = [], [f for f in fragments]
    while rest:
        chain = rest.pop(0)
        while np.hypot(*(chain[-1] - chain[0])) > snap or len(chain) < 4:
            if not rest:
                gap = np.hypot(*(chain[-1] - chain[0]))
                raise InvalidInputError(
                    f"{where}: outline cannot be closed: gap of {gap * scale:.3f} mm between "
                    f"{_fmt(chain[-1], unit)} and {_fmt(chain[0], unit)} exceeds the snap "
                    f"tolerance of {snap * scale:.3f} mm")
            d = [(np.hypot(*(f[0] - chain[-1])), i, False) for i, f in enumerate(rest)]
            d += [(np.hypot(*(f[-1] - chain[-1])), i, True) for i, f in enumerate(rest)]
            gap, i, flip = min(d, key=lambda t: t[0])
            close_gap = np.hypot(*(chain[-1] - chain[0]))
            if gap > snap:
                raise InvalidInputError(
                    f"{where}: outline cannot be closed: gap of {min(gap, close_gap) * scale:.3f} mm "
                    f"after {_fmt(chain[-1], unit)} exceeds the snap tolerance of "
                    f"{snap * scale:.3f} mm")
            nxt = rest.pop(i)
            chain = np.vstack([chain, (nxt[::-1] if flip else nxt)[1:]])
        loops.append(chain[:-1])
    return loops


def _fmt(p: np.ndarray, unit: str) -> str:
    return f"({p[0]:.4g}, {p[1]:.4g}) {unit}"


def read_generic(doc, tolerance: float, snap: float, unit: str, scale: float, source: str):
    """(name, size, ring, annotations) for every closed contour in model space."""
    closed, open_ = [], []
    for e in disassemble.recursive_decompose(doc.modelspace()):
        pts = flatten(e, tolerance)
        if pts is None:
            continue
        name = f"{e.dxftype()}_{e.dxf.handle or len(closed) + len(open_)}"
        (closed if np.hypot(*(pts[-1] - pts[0])) <= snap and len(pts) >= 4 else open_).append(
            (name, pts))
    rings = [(name, pts[:-1]) for name, pts in closed]
    if open_:
        where = f"{source}: open curves {', '.join(n for n, _ in open_[:5])}"
        for k, ring in enumerate(chain_loops([p for _, p in open_], snap, where, unit, scale)):
            rings.append((f"CHAIN_{k + 1}", ring))
    if not rings:
        raise InvalidInputError(f"{source}: no closed outline found in model space")
    return [(name, "", ring, {}) for name, ring in rings]
