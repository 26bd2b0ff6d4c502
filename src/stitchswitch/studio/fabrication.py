"""Fabrication Mode: hoop grouping of the design and export of the fabrication folder.

``hoopings`` runs the same grouping as ``stitchswitch fabricate`` (``grouping.group`` into
``fabricate.grouping_hoops`` on the footprints stretched by the material's eta, then
``order.order_hoopings``) for display;
``export`` calls ``layout.fabrication.fabricate.fabricate`` itself, so the folder is the one the
CLI writes for the same design and options; ``hooping_plan`` plans one hooping's stitches as
``fabricate`` does, for the page's stitch-plan preview (``stitch_preview``).
"""
from __future__ import annotations

import dataclasses

from stitchswitch.layout.embroidery import export as formats
from stitchswitch.layout.embroidery.machines import catalogue
from stitchswitch.layout.embroidery.patch_design import geometry_for
from stitchswitch.layout.embroidery.stitches import StitchParams
from stitchswitch.layout.fabrication.fabricate import FabricateOptions, fabricate, grouping_hoops
from stitchswitch.layout.fabrication.grouping.footprints import stretch
from stitchswitch.layout.fabrication.grouping.group import group
from stitchswitch.layout.fabrication.order import order_hoopings
from stitchswitch.layout.fabrication.plan import plan_hooping


def hoopings(design, options: FabricateOptions | None = None):
    """(grouping, stitching order) of ``design`` under ``options`` (mode, time limit, spacing)."""
    options = options or FabricateOptions()
    eta = float(design.material_object().eta)
    feet, pieces = stretch(design, eta, options.blank_margin_mm)
    grouping = group(feet, pieces, grouping_hoops(design, options), options.mode,
                     options.time_limit_s, options.spacing_mm)
    return grouping, order_hoopings(grouping.hoopings, feet)


def export(design, outdir, options: FabricateOptions | None = None, saved: bool = True):
    """Write the fabrication folder (``fabricate``). ``saved`` False: the design differs from
    its file, so the sheet names it as in memory rather than quoting the file's checksum."""
    if not saved:
        design = dataclasses.replace(design, path=None)
    return fabricate(design, outdir, options or FabricateOptions())


def hooping_outlines(order, eta: float) -> list:
    """((4, 2) sewing-field corners in relaxed garment mm, "hooping k (hoop)") for each hooping
    of a garment-mode order, in stitching order; free-mode hoopings are not on the garment."""
    import numpy as np

    out = []
    for k, h in enumerate(order.hoopings, start=1):
        if h.piece is None:
            continue
        w, hh = h.hoop.field_mm(0)
        corners = np.array([[-w / 2, -hh / 2], [w / 2, -hh / 2], [w / 2, hh / 2], [-w / 2, hh / 2]])
        out.append((h.to_piece(corners) / eta, f"{k}: {h.hoop.name}"))
    return out


def hooping_plan(design, order, k: int, options: FabricateOptions | None = None):
    """The stitch plan (``plan.HoopingPlan``) of hooping ``k`` (0-based) of ``order``, as
    ``fabricate`` plans it for its machine file (same geometry resolution and stitch speed)."""
    options = options or FabricateOptions()
    machine = catalogue(options.machines_file, formats.supported_formats()).machine(
        options.machine or design.machine.name)
    specs = {p.id: p for p in design.patches}
    return plan_hooping(order.hoopings[k], specs, lambda s: geometry_for(s, options.resolution_mm),
                        StitchParams(stitches_per_minute=machine.stitches_per_minute))
