"""Fabrication Mode: hoop grouping of the design and export of the fabrication folder.

``hoopings`` runs the same grouping as ``stitchswitch fabricate`` (``grouping.group`` on the
footprints stretched by the material's eta, then ``order.order_hoopings``) for display;
``export`` calls ``layout.fabrication.fabricate.fabricate`` itself, so the folder is the one the
CLI writes for the same design and options.
"""
from __future__ import annotations

import dataclasses

from stitchswitch.layout.embroidery import export as formats
from stitchswitch.layout.embroidery.machines import catalogue
from stitchswitch.layout.fabrication.fabricate import FabricateOptions, fabricate
from stitchswitch.layout.fabrication.grouping.footprints import stretch
from stitchswitch.layout.fabrication.grouping.group import group
from stitchswitch.layout.fabrication.order import order_hoopings


def _hoops(design, options: FabricateOptions):
    machine = catalogue(options.machines_file, formats.supported_formats()).machine(
        options.machine or design.machine.name)
    name = options.hoop or (design.machine.hoop if design.machine.name.lower()
                            == machine.name.lower() else None)
    return (machine.hoop(name),) if name else machine.hoops


def hoopings(design, options: FabricateOptions | None = None):
    """(grouping, stitching order) of ``design`` under ``options`` (mode, time limit, spacing)."""
    options = options or FabricateOptions()
    eta = float(design.material_object().eta)
    feet, pieces = stretch(design, eta)
    grouping = group(feet, pieces, _hoops(design, options), options.mode, options.time_limit_s,
                     options.spacing_mm)
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
