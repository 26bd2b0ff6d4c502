"""``stitchswitch edit`` and ``stitchswitch remove``: change or delete placed patches by id."""
from __future__ import annotations

import click

from stitchswitch.cli import options
from stitchswitch.cli.design.patch_report import patch_rows, warn_violations
from stitchswitch.cli.design.place import _numbers, check_point
from stitchswitch.cli.output import key_value_table
from stitchswitch.files.outputs import check_output_file, together
from stitchswitch.layout.garment.design_io import load_design, save_design
from stitchswitch.layout.garment.editing import edit_patch, remove_patches

_OUTPUT = click.option("--output", "-o", type=options.OutputFile(as_str=True), default=None,
                       metavar="FILE",
                       help="Write the result here [default: update DESIGN in place, "
                            "atomically].")


def _save(design, path, output):
    target = output or path
    if output is None:
        check_output_file(path, what="DESIGN")
    with together({"--output" if output else "DESIGN": target}) as tmp:
        save_design(design, next(iter(tmp.values())))
    return target


@click.command(cls=options.Command)
@click.argument("design", type=click.Path(dir_okay=False))
@click.argument("patch_id", metavar="ID")
@click.option("--at", "at", default=None, metavar="X,Y",
              help="New centre, garment mm on the relaxed fabric [default: unchanged].")
@click.option("--diameter", "-d", "diameter_mm", type=options.FINITE_FLOAT, default=None,
              metavar="MM", help="New diameter d on the pre-stretched fabric [default: unchanged].")
@click.option("--fill", "-p", type=options.FINITE_FLOAT, default=None, metavar="P",
              help="New fill fraction in (0, 1] [default: unchanged].")
@click.option("--piece", default=None, metavar="NAME",
              help="Move the patch to this piece [default: unchanged].")
@_OUTPUT
def edit(design, patch_id, at, diameter_mm, fill, piece, output):
    """Change patch ID of DESIGN: its centre, diameter, fill or piece. The id stays. Prints the
    patch as it now is and a Warning: line for every check rule it breaks (exit 0); input the
    patch cannot take (a centre far off its piece, a diameter outside the model's range) exits
    2 and changes nothing."""
    d = load_design(design)
    centre = _numbers(at, "--at", 2) if at else None
    new = edit_patch(d, patch_id, centre_mm=centre, diameter_mm=diameter_mm, fill=fill,
                     piece=piece)
    check_point(new, new.patch(patch_id))
    target = _save(new, design, output)
    rows = [("edited", patch_id)] + patch_rows(new, [new.patch(patch_id)]) + [("file", target)]
    click.echo(key_value_table(rows))
    warn_violations(new, [patch_id])


@click.command(cls=options.Command)
@click.argument("design", type=click.Path(dir_okay=False))
@click.argument("patch_ids", metavar="ID...", nargs=-1, required=True)
@_OUTPUT
def remove(design, patch_ids, output):
    """Remove patches from DESIGN by id; every other patch keeps its id."""
    d = load_design(design)
    new = remove_patches(d, patch_ids)
    target = _save(new, design, output)
    click.echo(key_value_table([("removed", ", ".join(patch_ids)),
                                ("patches", str(len(new.patches))), ("file", target)]))
