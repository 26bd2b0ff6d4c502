"""``stitchswitch import``: start a design file from a DXF garment pattern or a rectangle."""
from __future__ import annotations

import logging
import os

import click
import numpy as np

from stitchswitch.cli import options
from stitchswitch.cli.output import key_value_table
from stitchswitch.errors import InvalidInputError
from stitchswitch.files.outputs import together
from stitchswitch.layout.garment.design import VERSION, Design
from stitchswitch.layout.garment.design_io import save_design
from stitchswitch.layout.garment.dxf.reader import UNITS, import_dxf
from stitchswitch.layout.garment.piece_select import rectangle_piece, select_pieces
from stitchswitch.layout.garment.plausible import size_warning


def parse_rectangle(text: str) -> tuple[float, float]:
    """``"WxH"`` (mm) -> (W, H); a clear ``InvalidInputError`` otherwise."""
    parts = text.lower().replace(" ", "").split("x")
    try:
        w, h = (float(v) for v in parts)
    except ValueError:
        raise InvalidInputError(f"--rectangle {text!r}: expected WIDTHxHEIGHT in mm, "
                                "e.g. 300x200") from None
    return w, h


@click.command("import", cls=options.Command)
@click.argument("pattern", required=False, type=click.Path(dir_okay=False))
@click.option("--rectangle", default=None, metavar="WxH",
              help="Instead of a pattern: one rectangular piece, WIDTHxHEIGHT in mm.")
@click.option("--name", default="rectangle", show_default=True, metavar="NAME",
              help="Name of the --rectangle piece.")
@click.option("--size", default=None, metavar="SIZE", help="The pattern size to import (required when the "
                                           "file has several).")
@click.option("--pieces", default=None, metavar="NAME,...",
              help="Only these pieces (default: every piece of the size).")
@click.option("--units", type=click.Choice(sorted(UNITS)), default=None,
              help="Units of a DXF file that does not state them.")
@click.option("--output", "-o", type=options.OutputFile((".json",), "a design file is JSON", as_str=True),
              required=True, metavar="FILE",
              help="The design file to write.")
def import_cmd(pattern, rectangle, name, size, pieces, units, output):
    """Write a new design file (no patches yet) holding the pieces of the DXF PATTERN (AAMA/ASTM
    from Gerber AccuMark or CLO, or plain DXF), or one --rectangle. Outlines are in mm; each
    piece is listed with its bounding box in the design's frame (the coordinates --at takes),
    and a piece of implausible garment size gets a Warning: line (wrong units?)."""
    if (pattern is None) == (rectangle is None):
        raise InvalidInputError("give either a PATTERN file or --rectangle WxH (not both)")
    if rectangle is not None:
        if size or pieces or units:
            raise InvalidInputError("--size, --pieces and --units apply to a PATTERN file only")
        chosen = (rectangle_piece(*parse_rectangle(rectangle), name=name),)
        repairs = ()
    else:
        if not os.path.isfile(pattern):
            raise InvalidInputError(f"no such file: {pattern!r}")
        imported = import_dxf(pattern, units=units)
        names = [n.strip() for n in pieces.split(",") if n.strip()] if pieces else None
        chosen = select_pieces(imported, size, names)
        repairs = imported.repairs
    design = Design(VERSION, chosen, ())
    with together({"--output": output}) as tmp:
        save_design(design, tmp["--output"])
    rows = [("pieces", str(len(chosen)))]
    for p in chosen:
        (x0, y0), (x1, y1) = np.min(p.outline_mm, axis=0), np.max(p.outline_mm, axis=0)
        label = f"{p.name} (size {p.size})" if p.size else p.name
        rows.append(("piece", f"{label}: {x1 - x0:.1f} x {y1 - y0:.1f} mm, x {x0:.1f}..{x1:.1f},"
                              f" y {y0:.1f}..{y1:.1f} mm, {len(p.outline_mm)} points"))
    if repairs:
        rows.append(("repaired", f"{len(repairs)} problem(s) in the DXF file, e.g. {repairs[0]}"))
    rows.append(("file", output))
    click.echo(key_value_table(rows))
    for p in chosen if pattern is not None else ():      # a --rectangle is as typed
        warning = size_warning(p)
        if warning:
            logging.getLogger("stitchswitch").warning(warning)      # hidden by -q
