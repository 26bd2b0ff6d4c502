"""``stitchswitch fabricate``: group a design's patches into hoopings, order them, and write
one embroidery file per hooping with layouts and a fabrication sheet (docs/fabrication.md)."""
from __future__ import annotations

import click

from stitchswitch.cli import options
from stitchswitch.cli.output import key_value_table
from stitchswitch.layout.embroidery import export
from stitchswitch.layout.embroidery.machines import DEFAULT_MACHINE
from stitchswitch.layout.fabrication.fabricate import FabricateOptions, fabricate
from stitchswitch.layout.fabrication.grouping.group import MODES
from stitchswitch.layout.garment.design_io import load_design


@click.command(cls=options.Command)
@click.argument("design_path", metavar="DESIGN.json", type=click.Path(dir_okay=False))
@click.option("--machine", default=None, metavar="NAME",
              help=f"Machine of the catalogue (default: the design's, {DEFAULT_MACHINE} if it "
                   "names none).")
@click.option("--machines", "machines_file", type=click.Path(dir_okay=False), default=None,
              metavar="FILE", help="Your own machines (JSON, see docs/fabrication.md), added to "
                                   "the built-in catalogue.")
@click.option("--hoop", default=None, metavar="NAME",
              help="Use only this hoop (default: the design's machine.hoop, else all hoops).")
@click.option("--format", "fmt", default=None, metavar="FMT",
              help="Embroidery format (default: the machine's, jef for the 550E): "
                   + ", ".join(f + (" (experimental)" if f in export.EXPERIMENTAL else "")
                               for f in export.supported_formats()) + ".")
@click.option("--blank-margin", "blank_margin_mm", type=options.FINITE_FLOAT, default=None,
              metavar="MM", help="Hoop every piece as an uncut blank reaching MM past its outline "
                                 "(relaxed mm), so a hoop frame may clamp fabric outside the "
                                 "piece [default: the design's blank_margin_mm, 0: pieces "
                                 "hooped already cut out].")
@click.option("--mode", type=click.Choice(MODES), default="garment", show_default=True,
              help="garment: patches stay on the garment piece; free: patches packed on "
                   "separate fabric.")
@click.option("--time-limit", "time_limit_s", type=options.FINITE_FLOAT, default=10.0,
              show_default=True, metavar="S",
              help="Time for the grouping; when HiGHS is stopped a greedy grouping is used.")
@click.option("--spacing", "spacing_mm", type=options.FINITE_FLOAT, default=10.0,
              show_default=True, metavar="MM", help="Free mode: gap between patches.")
@click.option("--resolution", "resolution_mm", type=options.FINITE_FLOAT, default=5.0,
              show_default=True, metavar="MM", help="Triangle side of the tessellation.")
@click.option("--force", is_flag=True, help="Replace a non-empty output directory.")
@click.option("--output", "-o", "outdir", type=click.Path(file_okay=False), required=True,
              metavar="OUTDIR", help="Output directory (written as a whole).")
def fabricate_cmd(design_path, machine, machines_file, hoop, fmt, blank_margin_mm, mode,
                  time_limit_s, spacing_mm, resolution_mm, force, outdir):
    """Write the fabrication folder of DESIGN.json: per hooping an embroidery file and a
    layout (PNG, SVG), an overview, fabrication.md/.html and fabrication.json."""
    if not time_limit_s > 0:
        raise options.InputError(f"--time-limit {time_limit_s:g} must be positive")
    if blank_margin_mm is not None and blank_margin_mm < 0:
        raise options.InputError(f"--blank-margin {blank_margin_mm:g} must be >= 0")
    design = load_design(design_path)
    opts = FabricateOptions(machine, machines_file, hoop, fmt, mode, time_limit_s, spacing_mm,
                            resolution_mm, force, blank_margin_mm)
    res = fabricate(design, outdir, opts)
    rep, doc = res.grouping.report, res.doc
    gap = "n/a" if rep.mip_gap is None else f"{100 * rep.mip_gap:.2f} %"
    rows = [
        ("design", f"{doc.design.file} ({doc.totals.patches} patches)"),
        ("machine", f"{doc.machine.label}, format {doc.embroidery_format}"),
        ("mode", doc.mode),
        ("hoopings", f"{res.grouping.count} ({res.grouping.hoop_types} hoop type(s)); lower "
                     f"bound {rep.hoopings_lower_bound}; first-fit decreasing "
                     f"{rep.greedy_hoopings}"),
        ("grouping", f"{rep.method}, HiGHS {rep.status}, gap {gap}, {rep.candidates} candidates"),
        ("solve time", f"{rep.solve_s:.2f} s (limit {time_limit_s:g} s)"),
        ("note", rep.note),
    ]
    for h in doc.hoopings:
        turn = ", turned 90" if h.orientation_deg == 90 else ""
        rows.append((f"hooping {h.number}",
                     f"{h.hoop}{turn}: {', '.join(p.id for p in h.patches)}; "
                     f"{h.stitches} stitches, {h.time_min:.1f} min -> {h.files.embroidery}"))
    conf = doc.conflicts
    g = doc.grouping
    rows.append(("conflicts", ("none" if not conf else
                 f"{len(conf)}, the fewest possible (see fabrication.md)" if g.conflicts_exact
                 else f"{len(conf)}, the fewest found (see fabrication.md)")
                 + ("" if g.fewest_hoopings is None or g.fewest_hoopings == res.grouping.count
                    else f"; {g.fewest_hoopings} hooping(s) would leave "
                         f"{g.fewest_hoopings_conflicts}")))
    rows.append(("total", f"{doc.totals.stitches} stitches, {doc.totals.time_min:.1f} "
                          "min of stitching"))
    rows.append(("output", f"{outdir} ({len(res.files)} files)"))
    click.echo(key_value_table(rows))
