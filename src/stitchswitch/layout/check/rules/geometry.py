"""Rule ``geometry``: the patch can be tessellated at the check's resolution (for example, a
composite core that holds no triangle, or a conductive triangle index past the last triangle,
cannot). The geometries are shared with the feature rule and the small-pieces warning through
``geometry`` (cached) and ``tessellated``."""
from __future__ import annotations

from stitchswitch.errors import InvalidInputError
from stitchswitch.layout.check.violation import Violation

RULE = "geometry"
_cache: dict = {}


def _key(patch, resolution_mm):
    outline = None if patch.outline_mm is None else patch.outline_mm.tobytes()
    return (patch.diameter_mm, patch.fill, patch.composite, outline, patch.conductive,
            resolution_mm)


def geometry(patch, resolution_mm):
    """``patch_design.geometry_for`` with a small cache (identical patches share one), or the
    ``InvalidInputError`` it raised."""
    from stitchswitch.layout.embroidery.patch_design import geometry_for

    key = _key(patch, resolution_mm)
    if key not in _cache:
        if len(_cache) > 256:
            _cache.clear()
        try:
            _cache[key] = geometry_for(patch, resolution_mm)
        except InvalidInputError as exc:
            _cache[key] = exc
    return _cache[key]


def tessellated(design, resolution_mm):
    """(patch, geometry) for each patch of ``design`` that can be tessellated at
    ``resolution_mm``, in design order (the others are this rule's violations)."""
    for patch in design.patches:
        g = geometry(patch, resolution_mm)
        if not isinstance(g, InvalidInputError):
            yield patch, g


def check(design, limits, eta) -> list[Violation]:
    out = []
    for patch in design.patches:
        g = geometry(patch, limits.resolution_mm)
        if isinstance(g, InvalidInputError):
            out.append(Violation(RULE, "error", (patch.id,), (patch.piece,), float("nan"),
                                 limits.resolution_mm,
                                 f"patch {patch.id}: cannot be tessellated at "
                                 f"{limits.resolution_mm:g} mm: {g}",
                                 "change the composite core, the conductive selection or the "
                                 "resolution"))
    return out
