"""``stitchswitch layout``: the 2D layout of a design as PNG, SVG or PDF."""
from __future__ import annotations

import click

from stitchswitch.cli import options
from stitchswitch.cli.output import key_value_table
from stitchswitch.files.outputs import together

_EXTENSIONS = (".png", ".svg", ".pdf")


@click.command("layout", cls=options.Command)
@click.argument("design", type=click.Path(dir_okay=False))
@click.option("--output", "-o", type=options.OutputFile(_EXTENSIONS, "the layout is written as "
                                                        ".png, .svg or .pdf", as_str=True),
              required=True, metavar="FILE", help="Figure to write (.png, .svg or .pdf).")
def layout_cmd(design, output):
    """Draw DESIGN in 2D: pieces to scale with names on mm axes (the design's frame), each
    patch's footprint relaxed (filled, coloured by predicted height) and stretched (dashed)
    with its id, and the check's violations marked in red."""
    from stitchswitch.cli.design.patch_report import predicted_heights
    from stitchswitch.files.atomic import atomic_write_bytes
    from stitchswitch.layout.check.constraints import check_design
    from stitchswitch.layout.fabrication.design_view import design_view
    from stitchswitch.layout.garment.design_io import load_design

    d = load_design(design)
    found = check_design(d)
    heights = predicted_heights(d, d.patches)
    data = design_view(d, heights, found, output.rsplit(".", 1)[1].lower())
    with together({"--output": output}) as tmp:
        atomic_write_bytes(tmp["--output"], data)
    n_err = sum(v.severity == "error" for v in found)
    click.echo(key_value_table([
        ("design", f"{design}: {len(d.patches)} patch(es) on {len(d.pieces)} piece(s)"),
        ("check", f"{n_err} error(s), {len(found) - n_err} warning(s) (marked in red)"),
        ("figure", output)]))
