"""Snap-through of a patch by a contact plate, as in the paper's switching experiment, and
bistability (docs/fem-reference.md, "Switching").

* ``plate``: ``plate_radius_mm(d)`` (the documented radius rule), ``contact_solve`` (unilateral
  contact by an active set);
* ``states``: the frame holding the outer fabric (``held_problem``), ``bistability(patch, ...)
  -> Bistability`` (bistable, spring-back or flat), ``mirrored``, ``is_inverted``;
* ``path``: ``switching_path(patch, ...) -> SwitchingPath``: force-displacement curve,
  switching force (N), energy barrier (mJ), both states;
* ``path_plot``: ``curve_png(curve, verdict)``, ``write_curve_png``: the force-displacement
  curve as a PNG, byte-identical for the same curve, written atomically; ``path_csv``:
  ``curve_csv(curve, knit_stiffness_n_per_m)``, ``write_curve_csv``: the same curve as CSV;
* ``regions``: ``bistability_map(diameters, fills, ...) -> BistabilityMap``, its PNG and text;
* ``force_scale``: ``fit_force_scale(samples, ...) -> ForceScaleFit``: newtons from measured
  switching forces, validated on held-out rows.
"""
from stitchswitch.fem_reference.snap.path import SwitchingPath, switching_path
from stitchswitch.fem_reference.snap.plate import contact_solve, plate_radius_mm
from stitchswitch.fem_reference.snap.states import (
                                                    HOLD_FACTOR,
                                                    Bistability,
                                                    bistability,
                                                    held_problem,
                                                    is_inverted,
                                                    mirrored,
)

__all__ = ["HOLD_FACTOR", "Bistability", "SwitchingPath", "bistability", "contact_solve",
           "held_problem", "is_inverted", "mirrored", "plate_radius_mm", "switching_path"]
