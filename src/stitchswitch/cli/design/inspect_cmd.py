"""``stitchswitch inspect``: summarise any embroidery file pyembroidery can read
(``layout.embroidery.file_summary``): counts, where the stitches lie about the hoop centre,
the machine's hoops that hold them there, and the hoop a JEF header names."""
from __future__ import annotations

import json

import click

from stitchswitch.cli import options
from stitchswitch.cli.output import key_value_table
from stitchswitch.layout.embroidery.file_summary import summarise
from stitchswitch.layout.embroidery.hoop_spec import JEF_HOOP_CODES
from stitchswitch.layout.embroidery.machines import DEFAULT_MACHINE, catalogue


def _range(lo: float, hi: float) -> str:
    return f"{lo:+.1f}..{hi:+.1f}"


def _header(h) -> str:
    if h["field_mm"] is None:
        known = ", ".join(str(c) for c in sorted(JEF_HOOP_CODES))
        return f"code {h['code']} (not a published JEF hoop code: {known})"
    w, hh = h["field_mm"]
    names = ", ".join(h["catalogue_hoops"]) or "none of this machine's hoops"
    held = "the stitches lie inside it" if h["holds_stitches"] else \
        "the stitches reach OUTSIDE this field"
    return f"code {h['code']}, a {w:g} x {hh:g} mm field ({names}); {held}"


@click.command(cls=options.Command)
@click.argument("file", type=click.Path(dir_okay=False))
@click.option("--machine", default=DEFAULT_MACHINE, show_default=True, metavar="NAME",
              help="Machine of the catalogue whose hoops are tried.")
@click.option("--machines", "machines_file", type=click.Path(dir_okay=False), default=None,
              metavar="FILE", help="Your own machines (JSON, docs/fabrication.md), added to the "
                                   "built-in catalogue.")
@options.json_opt
def inspect(file, machine, machines_file, as_json):
    """Stitch count, colours, trims, the stitched extents about the hoop centre (the moves
    from the centre not counted), the hoops of the machine that hold the stitches where they
    lie, and the hoop a JEF file's header names."""
    m = catalogue(machines_file).machine(machine)
    s = summarise(file, m)
    if as_json:
        click.echo(json.dumps(dict(s, file=file), indent=2, allow_nan=False))
        return
    x0, y0, x1, y1 = s["stitch_bounds_mm"]
    fits = ", ".join(s["hoops"]) or f"no hoop of the {m.name} (largest: {m.largest_hoop()})"
    rows = [("stitches", str(s["stitches"])), ("jumps", str(s["jumps"])),
            ("trims", str(s["trims"])),
            ("colours", f"{s['colours']} ({s['colour_changes']} colour changes)"),
            ("extents", f"{s['width_mm']:.1f} x {s['height_mm']:.1f} mm of stitches"),
            ("position", f"x {_range(x0, x1)} mm, y {_range(y0, y1)} mm from the hoop centre"),
            ("fits", fits)]
    if s["centred_fit"] != s["hoops"] and s["centred_fit"]:
        rows.append(("centred", "moved to the hoop centre it would fit "
                     + ", ".join(s["centred_fit"])))
    if s["header_hoop"] is not None:
        rows.append(("header hoop", _header(s["header_hoop"])))
    click.echo(key_value_table(rows))
