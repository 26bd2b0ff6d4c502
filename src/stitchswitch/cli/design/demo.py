"""``stitchswitch demo [NAME]``: the paper's applications end to end (docs/guide.md)."""
from __future__ import annotations

import click

from stitchswitch.cli import options
from stitchswitch.demos.registry import DEMOS, get_demo


@click.command(cls=options.Command)
@click.argument("name", required=False, default=DEMOS[0], metavar="[NAME]")
@click.option("--output", "-o", "outdir", type=click.Path(file_okay=False), default=None,
              metavar="DIR", help="Output directory (default: ./stitchswitch-demo-NAME).")
@click.option("--force", is_flag=True, help="Replace a non-empty output directory.")
@click.option("--time-limit", "time_limit_s", type=options.FINITE_FLOAT, default=10.0,
              show_default=True, metavar="S", help="Time limit of the hoop-grouping MIP.")
def demo(name, outdir, force, time_limit_s):
    """Run a built-in demo: tennis-pocket (default; paper 6.1) or forearm-interface (6.2).

    Inverse design, placement on a garment piece, constraint check, 3D preview, hoop grouping,
    JEF export and a one-page HTML summary, into one output directory."""
    from stitchswitch.demos.pipeline import run_demo
    from stitchswitch.files.outdir import check_outdir

    spec = get_demo(name)
    outdir = outdir or f"stitchswitch-demo-{spec.name}"
    check_outdir(outdir, force)          # refuse before any work
    click.echo(f"stitchswitch demo {spec.name}: {spec.title} (paper, section {spec.paper_section})")
    run = run_demo(spec, outdir, force=force, echo=click.echo, time_limit_s=time_limit_s)
    click.echo(f"finished in {run.elapsed_s:.1f} s: {run.hoopings} hooping(s), "
               f"{run.violations} constraint violation(s)")
    click.echo(f"outputs in {run.outdir}/:")
    for f in run.files:
        if "/" not in f or f.endswith(("fabrication.html", ".jef")):
            click.echo(f"  {f}")
    click.echo(f"open {run.outdir}/summary.html for the one-page summary")
