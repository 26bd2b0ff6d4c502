"""``stitchswitch inspect``: summarise any embroidery file pyembroidery can read
(``layout.embroidery.file_summary``)."""
from __future__ import annotations

import click

from stitchswitch.cli import options
from stitchswitch.cli.output import key_value_table
from stitchswitch.layout.embroidery.file_summary import summarise
from stitchswitch.layout.embroidery.machines import default_machine


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
