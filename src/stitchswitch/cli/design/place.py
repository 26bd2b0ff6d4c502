"""``stitchswitch place``: add patches to a design at a point, on a grid or along a polyline."""
from __future__ import annotations

import click

from stitchswitch.cli import options
from stitchswitch.cli.output import key_value_table
from stitchswitch.errors import InvalidInputError
from stitchswitch.files.outputs import check_output_file, together
from stitchswitch.layout.garment.design import STATES
from stitchswitch.layout.garment.design_io import load_design, save_design
from stitchswitch.layout.garment.placement import place_along, place_at, place_grid


def _numbers(text: str, what: str, count: int | None = None) -> list[float]:
    import math
    try:
        vals = [float(v) for v in text.split(",")]
    except ValueError:
        raise InvalidInputError(f"{what} {text!r}: expected numbers separated by commas") from None
    if count is not None and len(vals) != count:
        raise InvalidInputError(f"{what} {text!r}: expected {count} numbers X,Y")
    if not all(math.isfinite(v) for v in vals):
        raise InvalidInputError(f"{what} {text!r}: not a finite number")
    return vals


#: The largest --grid: rows and columns each, and patches in all.
GRID_MAX_SIDE, GRID_MAX_PATCHES = 100, 1000


def _grid(text: str) -> tuple[int, int]:
    parts = text.lower().split("x")
    try:
        rows, cols = (int(v) for v in parts)
    except ValueError:
        raise InvalidInputError(f"--grid {text!r}: expected ROWSxCOLS, e.g. 3x4") from None
    if max(rows, cols) > GRID_MAX_SIDE or rows * cols > GRID_MAX_PATCHES:
        raise InvalidInputError(f"--grid {text!r}: at most {GRID_MAX_SIDE} rows and columns, "
                                f"{GRID_MAX_PATCHES} patches in all")
    return rows, cols


@click.command(cls=options.Command)
@click.argument("design", type=click.Path(dir_okay=False))
@click.option("--piece", required=True, help="The piece to place the patches on.")
@click.option("--at", "at", default=None, metavar="X,Y", help="One patch centred at X,Y (mm).")
@click.option("--grid", default=None, metavar="ROWSxCOLS",
              help=f"A grid of patches (--pitch): at most {GRID_MAX_SIDE} a side, {GRID_MAX_PATCHES} in all.")
@click.option("--centre", default=None, metavar="X,Y",
              help="Centre of the --grid (default: the piece's centroid).")
@click.option("--along", default=None, metavar="X,Y;X,Y;...",
              help="Patches every --pitch mm along this polyline, from its first point.")
@click.option("--pitch", "pitch_mm", type=options.FINITE_FLOAT, default=None, metavar="MM",
              help="Centre-to-centre distance for --grid and --along (garment mm).")
@click.option("--diameter", "-d", "diameter_mm", type=options.FINITE_FLOAT, required=True,
              metavar="MM", help="Patch diameter d on the pre-stretched fabric.")
@click.option("--fill", "-p", type=options.FINITE_FLOAT, required=True, metavar="P",
              help="Fill fraction in (0, 1].")
@click.option("--conductive", default=None, metavar="SPEC",
              help="Conductive triangles: index:I,J | ring:K,.. | annulus:IN:OUT | polygon:...")
@click.option("--state", type=click.Choice(STATES), default="up", show_default=True,
              help="The stable state shown in previews.")
@click.option("--id-prefix", default="p", show_default=True,
              help="New ids are PREFIX1, PREFIX2, ... after the largest in use.")
@click.option("--output", "-o", type=options.OutputFile(as_str=True), default=None, metavar="FILE",
              help="Write the result here (default: update DESIGN in place, atomically).")
def place(design, piece, at, grid, centre, along, pitch_mm, diameter_mm, fill, conductive,
          state, id_prefix, output):
    """Add patches to the DESIGN file on one piece. Positions are garment mm on the relaxed
    fabric (the piece outline's coordinates)."""
    modes = [m for m, v in (("--at", at), ("--grid", grid), ("--along", along)) if v is not None]
    if len(modes) != 1:
        raise InvalidInputError("give exactly one of --at X,Y, --grid ROWSxCOLS or --along "
                                "X,Y;X,Y;..." + (f" (got {', '.join(modes)})" if modes else ""))
    if (grid or along) and pitch_mm is None:
        raise InvalidInputError(f"{modes[0]} needs --pitch MM")
    if at and pitch_mm is not None:
        raise InvalidInputError("--pitch applies to --grid and --along only")
    if centre and not grid:
        raise InvalidInputError("--centre applies to --grid only")
    target = output or design
    if output is None:
        check_output_file(design, what="DESIGN")      # updated in place: writable?
    d = load_design(design)
    before = len(d.patches)
    extra = dict(conductive=conductive, state=state, id_prefix=id_prefix)
    if at:
        d = place_at(d, piece, _numbers(at, "--at", 2), diameter_mm, fill, **extra)
    elif grid:
        c = _numbers(centre, "--centre", 2) if centre else None
        d = place_grid(d, piece, *_grid(grid), pitch_mm, diameter_mm, fill, centre_mm=c, **extra)
    else:
        pts = [_numbers(p, "--along point", 2) for p in along.split(";") if p.strip()]
        d = place_along(d, piece, pts, pitch_mm, diameter_mm, fill, **extra)
    with together({"--output" if output else "DESIGN": target}) as tmp:
        save_design(d, next(iter(tmp.values())))
    new = d.patches[before:]
    rows = [("added", f"{len(new)} patch(es) on {piece}: d = {diameter_mm:g} mm, fill = {fill:g}")]
    rows += [(p.id, f"({p.centre_mm[0]:.2f}, {p.centre_mm[1]:.2f})") for p in new]
    rows += [("patches", str(len(d.patches))), ("file", target)]
    click.echo(key_value_table(rows))
