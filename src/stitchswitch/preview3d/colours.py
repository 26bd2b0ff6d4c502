"""Colour maps of the preview: height, or the patches and pieces that violate the constraints.

``height``: matplotlib's diverging ``coolwarm``, grey at the flat fabric. With patches both up
and down it spans (-H, H), H the largest |apex height| (``height_clim``); with every patch up the
colour bar runs from 0 to the largest height over the map's upper (grey to red) half, with every
patch down from the lowest height to 0 over its lower half, so no range is shown that no patch
reaches (``height_scale``). Without patches there is nothing to colour and no colour bar.

``violations``: the constraint check of the design (``layout.check.constraints.check_design``): the
embroidered part of a patch (rest radius <= R_b) is red if an error names the patch, orange if
only a warning does, green otherwise; its blend into the fabric stays grey. A piece named by a
violation that names no patch (a problem of the piece itself) is tinted like its worst one,
other fabric is grey.
"""
from __future__ import annotations

import numpy as np

from stitchswitch.errors import InvalidInputError

COLOURS = ("height", "violations")
HEIGHT_CMAP = "coolwarm"
STATUS_RGB = {"ok": (44, 160, 44), "warning": (255, 158, 36), "error": (214, 39, 40)}
FABRIC_RGB = {"ok": (217, 217, 217), "warning": (250, 222, 180), "error": (245, 190, 190)}
_RANK = {"ok": 0, "warning": 1, "error": 2}


def check_colour(colour: str) -> str:
    if colour not in COLOURS:
        raise InvalidInputError(f"color: {colour!r} is not one of " + ", ".join(COLOURS))
    return colour


def height_clim(scene) -> tuple[float, float]:
    h = max([abs(p.height_mm) for p in scene.patches] + [1e-3])
    return -h, h


def height_scale(scene):
    """(colour map, clim) of the height colouring: the half of ``HEIGHT_CMAP`` on the side the
    patches pop to when they all pop the same way, the whole map about 0 otherwise; None for
    a scene without patches."""
    import matplotlib
    from matplotlib.colors import ListedColormap

    heights = [p.height_mm for p in scene.patches]
    if not heights:
        return None
    full = matplotlib.colormaps[HEIGHT_CMAP]
    lo, hi = min(heights), max(heights)
    if lo >= 0.0:
        return ListedColormap(full(np.linspace(0.5, 1.0, 128)), "coolwarm-up"), (0.0, max(hi, 1e-3))
    if hi <= 0.0:
        return ListedColormap(full(np.linspace(0.0, 0.5, 128)), "coolwarm-down"), (min(lo, -1e-3), 0.0)
    return full, height_clim(scene)


def status_from_violations(violations) -> tuple[dict, dict]:
    """({patch id: status}, {piece name: status}) of the worst violation naming each."""
    patches: dict[str, str] = {}
    pieces: dict[str, str] = {}
    for v in violations:
        sev = v.severity if v.severity in _RANK else "error"
        # a piece is tinted only by its own problems; a patch's problem colours the patch
        for table, names in ((patches, v.patches), (pieces, () if v.patches else v.pieces)):
            for name in names:
                if _RANK[sev] > _RANK[table.get(name, "ok")]:
                    table[name] = sev
    return patches, pieces


def design_status(design) -> tuple[dict, dict, list]:
    """Run the design's constraint check; (patch status, piece status, violations)."""
    try:
        from stitchswitch.layout.check.constraints import check_design
    except ImportError:
        raise InvalidInputError("color 'violations': the constraint check "
                                "(stitchswitch.layout.check.constraints) is not available") from None
    violations = list(check_design(design))
    patches, pieces = status_from_violations(violations)
    return patches, pieces, violations


def point_rgb(scene, patch_status: dict, piece_status: dict) -> np.ndarray:
    """(n, 3) uint8 colour of every point of ``scene.merged()``."""
    rows = [np.tile(FABRIC_RGB[piece_status.get(p.name, "ok")], (len(p.points), 1))
            for p in scene.pieces]
    for p in scene.patches:
        inside = p.surface.rest_radius_mm <= p.profile.boundary_radius_mm * (1 + 1e-9)
        rows.append(np.where(inside[:, None], STATUS_RGB[patch_status.get(p.id, "ok")],
                             FABRIC_RGB["ok"]))
    return np.vstack(rows).astype(np.uint8) if rows else np.zeros((0, 3), np.uint8)
