"""What ``place`` and ``edit`` print about the patches they touched: the predicted keypoints
(the design map, or a direct solve outside it: ``preview3d.profiles``), the footprint on the
relaxed and the stretched fabric, and one ``Warning:`` line (stderr, through the package's
logger, so -q hides it) per violation of the
constraint check that names one of them."""
from __future__ import annotations

import logging

from stitchswitch.reduced.model.params import DIAMETER_RANGE_MM


def _profiles(design, patches) -> dict:
    """Patch id -> predicted profile, for the patches inside the model's range."""
    from stitchswitch.preview3d.profiles import patch_profiles

    lo, hi = DIAMETER_RANGE_MM
    inside = [p for p in patches if lo <= p.diameter_mm <= hi]
    if not inside:
        return {}
    return dict(zip((p.id for p in inside), patch_profiles(
        [p.diameter_mm for p in inside], [p.fill for p in inside], design.material_object())))


def predicted_heights(design, patches) -> dict:
    """Patch id -> predicted h (mm), None outside the model's range."""
    profiles = _profiles(design, patches)
    return {p.id: (profiles[p.id].keypoints.h_mm if p.id in profiles else None)
            for p in patches}


def patch_rows(design, patches) -> list[tuple[str, str]]:
    """One row per patch: centre, d and fill, predicted h and r_a, footprints (mm)."""
    material = design.material_object()
    profiles = _profiles(design, patches)
    rows = []
    for p in patches:
        where = f"({p.centre_mm[0]:.2f}, {p.centre_mm[1]:.2f}) on {p.piece}"
        size = f"d = {p.diameter_mm:g} mm, fill = {p.fill:g}"
        if p.id in profiles:
            kp = profiles[p.id].keypoints
            shape = f"h = {kp.h_mm:.2f} mm, r_a = {kp.r_a_mm:.2f} mm"
        else:
            shape = "shape not predicted (outside the model's range)"
        foot = (f"footprint {p.diameter_mm / material.eta:.1f} mm relaxed, "
                f"{p.diameter_mm:g} mm stretched")
        rows.append((p.id, f"{where}; {size}; {shape}; {foot}"))
    return rows


def warn_violations(design, ids) -> int:
    """Echo ``Warning: <rule>: <message>; fix: <hint>`` for every violation naming a patch of
    ``ids``; the number of lines."""
    from stitchswitch.layout.check.constraints import check_design

    ids = set(ids)
    n = 0
    for v in check_design(design):
        if ids & set(v.patches):
            hint = f"; fix: {v.hint}" if v.hint else ""
            logging.getLogger("stitchswitch").warning(f"{v.rule}: {v.message}{hint}")
            n += 1
    return n
