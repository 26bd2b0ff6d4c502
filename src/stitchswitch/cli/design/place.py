"""``stitchswitch place``: add patches to a design at a point, on a grid or along a polyline."""
from __future__ import annotations

import click

from stitchswitch.cli import options
from stitchswitch.cli.design.patch_report import patch_rows, warn_violations
from stitchswitch.cli.output import key_value_table
from stitchswitch.errors import InvalidInputError
from stitchswitch.files.outputs import check_output_file, together
from stitchswitch.layout.garment.design import STATES
from stitchswitch.layout.garment.design_io import load_design, save_design
from stitchswitch.layout.garment.placement import place_along, place_at, place_grid
from stitchswitch.reduced.model.params import DIAMETER_RANGE_MM


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
@click.option("--piece", required=True, metavar="NAME", help="The piece to place the patches on.")
@click.option("--at", "at", default=None, metavar="X,Y", help="One patch centred at X,Y (mm).")
@click.option("--grid", default=None, metavar="ROWSxCOLS",
              help=f"A grid of patches (--pitch): at most {GRID_MAX_SIDE} a side, {GRID_MAX_PATCHES} in all.")
@click.option("--center", "centre", default=None, metavar="X,Y",
              help="Center of the --grid, garment mm [default: the piece's centroid].")
@options.deprecated_alias("--centre", "--center")("centre_old")
@click.option("--along", default=None, metavar="X,Y;X,Y;...",
              help="Patches every --pitch mm along this polyline, from its first point.")
@click.option("--pitch", "pitch_mm", type=options.FINITE_FLOAT, default=None, metavar="MM",
              help="Centre-to-centre distance for --grid and --along (garment mm).")
@click.option("--diameter", "-d", "diameter_mm", type=options.FINITE_FLOAT, default=None,
              metavar="MM", help="Patch diameter d on the pre-stretched fabric (with --fill; or "
                                 "give --height).")
@click.option("--fill", "-p", type=options.FINITE_FLOAT, default=None, metavar="P",
              help="Fill fraction in (0, 1] (with --diameter).")
@click.option("--height", "height_mm", type=options.FINITE_FLOAT, default=None, metavar="MM",
              help="Instead of -d/-p: inverse-design a patch of this peak height h under the "
                   "check's rules at the position and place the best that passes them.")
@options.inverse_target_opts("With --height: ")
@click.option("--conductive", default=None, metavar="SPEC",
              help="Conductive triangles: index:I,J | ring:K,.. | annulus:IN:OUT | polygon:...")
@click.option("--state", type=click.Choice(STATES), default="up", show_default=True,
              help="The stable state shown in previews.")
@click.option("--id-prefix", default="p", show_default=True, metavar="PREFIX",
              help="New ids are PREFIX1, PREFIX2, ... after the largest in use.")
@click.option("--output", "-o", type=options.OutputFile((".json",), "a design file is JSON", as_str=True),
              default=None, metavar="FILE",
              help="Write the result here [default: update DESIGN in place, atomically].")
def place(design, piece, at, grid, centre, centre_old, along, pitch_mm, diameter_mm, fill, height_mm,
          radius_mm, max_diameter_mm, min_fill, conductive, state, id_prefix, output):
    """Add patches to the DESIGN file on one piece. Positions are garment mm on the relaxed
    fabric (the piece outline's coordinates). Prints each new patch's predicted height and
    footprint and a Warning: line for every check rule it breaks (exit 0); a centre off the
    piece or a diameter outside the model's range exits 2 and adds nothing."""
    if centre_old is not None:
        centre = options.one_of(centre, centre_old, "--center", "--centre")
    modes = [m for m, v in (("--at", at), ("--grid", grid), ("--along", along)) if v is not None]
    if len(modes) != 1:
        raise InvalidInputError("give exactly one of --at X,Y, --grid ROWSxCOLS or --along "
                                "X,Y;X,Y;..." + (f" (got {', '.join(modes)})" if modes else ""))
    if (grid or along) and pitch_mm is None:
        raise InvalidInputError(f"{modes[0]} needs --pitch MM")
    if at and pitch_mm is not None:
        raise InvalidInputError("--pitch applies to --grid and --along only")
    if centre and not grid:
        raise InvalidInputError("--center applies to --grid only")
    inverse_opts = {"--radius": radius_mm, "--max-diameter": max_diameter_mm,
                    "--min-fill": min_fill}
    if height_mm is None:
        if diameter_mm is None or fill is None:
            raise InvalidInputError("give --diameter and --fill, or --height")
        extra_opts = [k for k, v in inverse_opts.items() if v is not None]
        if extra_opts:
            raise InvalidInputError(f"{extra_opts[0]} applies to --height only")
    elif diameter_mm is not None or fill is not None:
        raise InvalidInputError("give --height or --diameter/--fill, not both")
    target = output or design
    if output is None:
        check_output_file(design, what="DESIGN")      # updated in place: writable?
    d = load_design(design)
    before = len(d.patches)
    extra = dict(conductive=conductive, state=state, id_prefix=id_prefix)
    if height_mm is not None:
        from stitchswitch.layout.check.height_placement import place_for_height
        from stitchswitch.reduced.design_space.inverse import InverseTarget

        if not at:
            raise InvalidInputError("--height places one patch: give --at X,Y")
        goal = InverseTarget(height_mm, radius_mm, max_diameter_mm, min_fill, count=5)
        d, chosen = place_for_height(d, piece, _numbers(at, "--at", 2), goal, **extra)
        diameter_mm, fill = chosen.diameter_mm, chosen.fill
    elif at:
        d = place_at(d, piece, _numbers(at, "--at", 2), diameter_mm, fill, **extra)
    elif grid:
        c = _numbers(centre, "--center", 2) if centre else None
        d = place_grid(d, piece, *_grid(grid), pitch_mm, diameter_mm, fill, centre_mm=c, **extra)
    else:
        pts = [_numbers(p, "--along point", 2) for p in along.split(";") if p.strip()]
        d = place_along(d, piece, pts, pitch_mm, diameter_mm, fill, **extra)
    new = d.patches[before:]
    for p in new:
        check_point(d, p)
    with together({"--output" if output else "DESIGN": target}) as tmp:
        save_design(d, next(iter(tmp.values())))
    rows = [("added", f"{len(new)} patch(es) on {piece}: d = {diameter_mm:g} mm, fill = {fill:g}"
                      + (f" (inverse design for h = {height_mm:g} mm)" if height_mm else ""))]
    rows += patch_rows(d, new)
    rows += [("patches", str(len(d.patches))), ("file", target)]
    click.echo(key_value_table(rows))
    warn_violations(d, [p.id for p in new])


def check_point(design, patch) -> None:
    """Refuse what no fix of the layout can make work: a diameter outside the model's range,
    or a centre so far off its piece that the footprint does not touch it."""
    import shapely

    lo, hi = DIAMETER_RANGE_MM
    if not lo <= patch.diameter_mm <= hi:
        raise InvalidInputError(f"patch {patch.id}: d = {patch.diameter_mm:g} mm is outside the "
                                f"model's range [{lo:g}, {hi:g}] mm")
    poly = shapely.make_valid(shapely.Polygon(design.piece(patch.piece).outline_mm))
    eta = design.material_object().eta
    off = float(poly.distance(shapely.Point(*patch.centre_mm)))
    if off > patch.diameter_mm / (2 * eta):
        x0, y0, x1, y1 = poly.bounds
        raise InvalidInputError(
            f"patch {patch.id}: the centre ({patch.centre_mm[0]:g}, {patch.centre_mm[1]:g}) is "
            f"{off:.1f} mm outside piece {patch.piece} (its bounding box is x {x0:.1f}..{x1:.1f},"
            f" y {y0:.1f}..{y1:.1f} mm)")
