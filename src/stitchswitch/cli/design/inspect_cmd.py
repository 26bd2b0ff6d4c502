"""``stitchswitch inspect``: summarise any embroidery file pyembroidery can read."""
from __future__ import annotations

import pathlib

import click

from stitchswitch.cli import options
from stitchswitch.cli.output import key_value_table
from stitchswitch.errors import InvalidInputError
from stitchswitch.layout.embroidery.machines import default_machine


def summarise(path) -> dict:
    import pyembroidery as pe
    path = pathlib.Path(path)
    if not path.is_file():
        raise InvalidInputError(f"no such file: {str(path)!r}")
    settings = {"trims": True} if path.suffix.lower() == ".jef" else None
    try:
        pattern = pe.read(str(path), settings)
    except Exception as exc:  # pyembroidery raises anything on malformed input
        raise InvalidInputError(f"cannot read {str(path)!r}: {exc}") from None
    if pattern is None:
        raise InvalidInputError(f"{str(path)!r} is not a readable embroidery file")
    cmds = [s[2] & pe.COMMAND_MASK for s in pattern.stitches]
    n_stitch = cmds.count(pe.STITCH)
    if not pattern.stitches:
        raise InvalidInputError(f"{str(path)!r} holds no stitches")
    x0, y0, x1, y1 = pattern.bounds()
    w, h = (x1 - x0) / 10.0, (y1 - y0) / 10.0
    return {"stitches": n_stitch, "jumps": cmds.count(pe.JUMP), "trims": cmds.count(pe.TRIM),
            "colour_changes": cmds.count(pe.COLOR_CHANGE),
            "colours": max(len(pattern.threadlist), cmds.count(pe.COLOR_CHANGE) + 1),
            "width_mm": w, "height_mm": h,
            "hoops": [str(hp) for hp in default_machine().hoops_fitting(w, h)]}


@click.command(cls=options.Command)
@click.argument("file", type=click.Path(dir_okay=False))
def inspect(file):
    """Stitch count, colours, trims, extents and the 550E hoops the FILE fits."""
    s = summarise(file)
    rows = [("stitches", str(s["stitches"])), ("jumps", str(s["jumps"])),
            ("trims", str(s["trims"])),
            ("colours", f"{s['colours']} ({s['colour_changes']} colour changes)"),
            ("extents", f"{s['width_mm']:.1f} x {s['height_mm']:.1f} mm"),
            ("fits", ", ".join(s["hoops"]) or f"no hoop (largest: {default_machine().largest_hoop()})")]
    click.echo(key_value_table(rows))
