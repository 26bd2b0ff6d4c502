"""The force-displacement curve of a switching path as CSV: a ``#`` comment line naming the
reference, the plate radius, the knit stiffness (the force scale) and the design, then
``w_mm,force_N`` rows (plate height in mm, contact force in newtons), written atomically."""
from __future__ import annotations

from stitchswitch.files.atomic import atomic_write_text

__all__ = ["curve_csv", "write_curve_csv"]


def curve_csv(curve, knit_stiffness_n_per_m: float) -> str:
    """The CSV text of ``curve`` (``path.SwitchingPath``), computed with the knit stiffness
    ``knit_stiffness_n_per_m`` (N/m) that its newtons rest on."""
    force_n = curve.force * curve.newton_per_n
    rows = "\n".join(f"{w:.6f},{f:.9g}" for w, f in zip(curve.w_mm, force_n))
    return ("# stitchswitch switch-force, shell of revolution, plate radius "
            f"{curve.plate_radius_mm:.2f} mm, knit stiffness {knit_stiffness_n_per_m:g} N/m, "
            f"d_mm={curve.patch.diameter_mm:g}, fill={curve.patch.fill:g}\n"
            f"w_mm,force_N\n{rows}\n")


def write_curve_csv(path, curve, knit_stiffness_n_per_m: float) -> None:
    """``curve_csv`` written to ``path`` atomically."""
    atomic_write_text(path, curve_csv(curve, knit_stiffness_n_per_m))
