"""``stitchswitch check``: the constraint check of a design file (exit 0 clean, 1 violations)."""
from __future__ import annotations

import dataclasses
import json
import math

import click

from stitchswitch.cli import options
from stitchswitch.layout.check.constraints import CheckLimits
from stitchswitch.layout.check.report import check_report
from stitchswitch.layout.garment.design_io import load_design

_DEFAULT = CheckLimits()


def _limit_opt(name: str, field: str, help_text: str):
    return click.option(name, field, type=options.FINITE_FLOAT, default=getattr(_DEFAULT, field),
                        show_default=True, metavar="MM", help=help_text)


@click.command(cls=options.Command)
@click.argument("design", type=click.Path(dir_okay=False))
@options.json_opt
@_limit_opt("--seam-allowance", "seam_allowance_mm", "Seam allowance along piece outlines.")
@_limit_opt("--edge-clearance", "edge_clearance_mm",
            "Extra clearance between the seam allowance and a patch footprint.")
@_limit_opt("--min-spacing", "min_spacing_mm",
            "Bare fabric between patches (relaxed, edge to edge).")
@_limit_opt("--min-gap", "min_gap_mm", "Smallest gap between stitched triangles (hoop mm).")
@_limit_opt("--min-side", "min_side_mm", "Smallest stitched triangle side (hoop mm).")
@click.option("--hoop-margin", "hoop_margin_mm", type=options.FINITE_FLOAT, default=None,
              metavar="MM", help="Margin inside the hoop field (default: the hoop's own, "
                                 "from the machine catalogue).")
@_limit_opt("--resolution", "resolution_mm", "Triangle side of the tessellation.")
@click.option("--blank-margin", "blank_margin_mm", type=options.FINITE_FLOAT, default=None,
              metavar="MM", help="Judge hoopability with every piece hooped as an uncut blank "
                                 "reaching MM past its outline, as fabricate --blank-margin "
                                 "[default: the design's blank_margin_mm].")
def check(design, as_json, blank_margin_mm, **limits):
    """Check DESIGN: diameters in the model's range, patches inside their pieces with an edge
    margin, spacing between patches, triangle sides and gaps the machine can form, hoop fit,
    that every patch can be hooped where it lies (the frame on the piece, or on its uncut
    blank: the design's blank_margin_mm), and pairs of patches whose hoop frames must press
    one another (a warning). Each violation names its patch and a fix. Patches with stitched
    pieces under 1 mm^2 are warned about as fabricate's sheet does (not a violation). Every error is
    something fabricate refuses or the model cannot predict. Exit code 0 when clean,
    1 when there are violations, 2 for bad input."""
    lim = CheckLimits(**limits)
    if blank_margin_mm is not None and blank_margin_mm < 0:
        raise options.InputError(f"--blank-margin {blank_margin_mm:g} must be >= 0")
    d = load_design(design)
    if blank_margin_mm is not None:
        d = dataclasses.replace(d, blank_margin_mm=blank_margin_mm)
    report = check_report(d, lim)
    found, small, errors = report.violations, report.small_pieces, report.errors
    if as_json:
        body = report.as_dict()
        out = {"design": design, "patches": len(d.patches), "pieces": len(d.pieces),
               "limits": body.pop("limits"), "blank_margin_mm": d.blank_margin_mm, **body}
        click.echo(json.dumps(out, indent=2, allow_nan=False))
    else:
        if found:
            click.echo(_table(found))
        for w in small:
            click.echo(w.line)
        click.echo(f"{len(d.patches)} patch(es) on {len(d.pieces)} piece(s): "
                   + ("no violation" if not found else
                      f"{errors} error(s), {len(found) - errors} warning(s)")
                   + (f"; small pieces in {len(small)} patch(es)" if small else ""))
    if found:
        click.get_current_context().exit(1)


def _table(found) -> str:
    head = ("severity", "rule", "patches", "pieces", "value mm", "limit mm", "message")
    rows = [(v.severity, v.rule, ",".join(v.patches), ",".join(v.pieces),
             "-" if not math.isfinite(v.value) else f"{v.value:.2f}", f"{v.limit:g}", v.message)
            for v in found]
    widths = [max(len(r[i]) for r in (head, *rows)) for i in range(len(head) - 1)]
    lines = ["  ".join(c.ljust(w) for c, w in zip(head[:-1], widths)) + "  " + head[-1]]
    for v, r in zip(found, rows):
        lines.append("  ".join(c.ljust(w) for c, w in zip(r[:-1], widths)) + "  " + r[-1])
        if v.hint:
            lines.append(" " * (sum(widths) + 2 * len(widths)) + "fix: " + v.hint)
    return "\n".join(lines)
