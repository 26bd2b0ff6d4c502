"""The check's rules for one plain circular design (d, p) before it is placed: what inverse
design needs to leave out designs that the check would flag once placed.

``admissible(limits, hoops)`` returns ``rule_broken(d, p) -> str | None``: the rule a patch of
diameter d and fill p breaks wherever it is placed (``feature-side``, ``feature-gap`` at the
limits' resolution, from the same tessellation as the check; ``hoop-fit`` in the roomiest of
``hoops``), or None. Placement rules (piece edge, spacing, hoopability) depend on the position
and are judged when the patch is placed.
"""
from __future__ import annotations

from functools import lru_cache

from stitchswitch.errors import InvalidInputError
from stitchswitch.layout.check.constraints import CheckLimits
from stitchswitch.layout.check.rules.features import feature_sizes
from stitchswitch.layout.check.rules.geometry import geometry
from stitchswitch.layout.garment.design import PatchSpec

__all__ = ["admissible", "for_machine"]


def admissible(limits: CheckLimits | None = None, hoops=None):
    """``rule_broken(d, p) -> str | None`` under ``limits`` (None: the defaults) and ``hoops``
    (None: no hoop rule)."""
    limits = limits or CheckLimits()
    side_mm = None
    if hoops:
        def usable(h):
            m = limits.hoop_margin_mm if limits.hoop_margin_mm is not None else h.margin_mm
            return min(h.width_mm, h.height_mm) - 2 * m, h
        side_mm, roomiest = max((usable(h) for h in hoops), key=lambda t: t[0])

    @lru_cache(maxsize=4096)
    def rule_broken(diameter_mm: float, fill: float) -> str | None:
        if side_mm is not None and diameter_mm > side_mm + 1e-9:
            return (f"hoop-fit: {diameter_mm:g} mm exceeds the {side_mm:g} mm the roomiest hoop "
                    f"{roomiest.name} holds inside its margin")
        g = geometry(PatchSpec("candidate", "-", (0.0, 0.0), diameter_mm, fill),
                     limits.resolution_mm)
        if isinstance(g, InvalidInputError):
            return f"geometry: {g}"
        side, gap = feature_sizes(g)
        if side < limits.min_side_mm - 1e-9:
            return (f"feature-side: triangles under {limits.min_side_mm:g} mm at resolution "
                    f"{limits.resolution_mm:g} mm")
        if gap is not None and gap < limits.min_gap_mm - 1e-9:
            return (f"feature-gap: gaps under {limits.min_gap_mm:g} mm between triangles at "
                    f"resolution {limits.resolution_mm:g} mm")
        return None

    return lambda d, p: rule_broken(round(float(d), 9), round(float(p), 9))


def for_machine(machine: str | None = None, resolution_mm: float = 5.0, hoop: str | None = None):
    """``admissible`` under the default limits at ``resolution_mm``, in the hoops of
    ``machine`` (built-in catalogue; default: the default machine), or in ``hoop`` alone."""
    from stitchswitch.layout.embroidery.machines import DEFAULT_MACHINE, builtin_catalogue

    m = builtin_catalogue().machine(machine or DEFAULT_MACHINE)
    hoops = (m.hoop(hoop),) if hoop else m.hoops
    return admissible(CheckLimits(resolution_mm=resolution_mm), hoops)
