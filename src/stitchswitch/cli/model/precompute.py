"""``stitchswitch precompute``: solve the design grid and write the map (.npz)."""
from __future__ import annotations

import json
import time

import click

from stitchswitch.cli import options, progress
from stitchswitch.executor import default_workers
from stitchswitch.files.outputs import check_distinct, together
from stitchswitch.reduced.design_space import precompute as build_map
from stitchswitch.reduced.design_space import smoothness as map_check
from stitchswitch.reduced.design_space import storage as map_io
from stitchswitch.reduced.model.material_io import load_material
from stitchswitch.reduced.model.params import DEFAULT_MATERIAL


@click.command(cls=options.Command)
@options.material_opt
@click.option("--diameters", default="15:100:1", show_default=True, metavar="START:STOP:STEP",
              help=f"Diameters in mm (inclusive range, at most {build_map.MAX_AXIS_POINTS} values).")
@click.option("--fills", default="0.5:1.0:0.01", show_default=True, metavar="START:STOP:STEP",
              help=f"Fill fractions (inclusive range, at most {build_map.MAX_AXIS_POINTS} values).")
@click.option("--workers", type=click.IntRange(min=1), default=None, metavar="N",
              help="Worker processes (default: one per core).")
@click.option("--scheduler", default=None, metavar="tcp://HOST:PORT",
              help="Solve on a Dask distributed cluster instead of local processes.")
@click.option("--output", "-o", "out", type=options.OutputFile((".npz",)), default=None,
              metavar="FILE.npz", help="Output map (.npz). Required.")
@options.deprecated_alias("--out", "-o/--output")("out_old", type=options.OutputFile((".npz",)))
@click.option("--plot", type=options.OutputFile((".png",)), default=None, metavar="PNG",
              help="Also write the h(d, p) heatmap (written together with -o: both or "
                   "neither).")
@click.option("--cold-start", is_flag=True,
              help="Solve every point from the released state, exactly as a direct solve "
                   "(default: each diameter along increasing fill, warm-started from the "
                   "previous equilibrium).")
@options.json_opt
def precompute(material_path, diameters, fills, workers, scheduler, out, out_old, plot,
               cold_start, as_json):
    """Solve every (d, p) of the grid and write the design-space map.

    Every point is a certified solve; points that fail the neighbour-mean smoothness test are
    listed with their explanation (buckling onset, branch change, under-resolved).
    """
    out = options.one_of(out, out_old, "-o/--output", "--out")
    outputs = {"--output": out, "--plot": plot}
    check_distinct(outputs)
    material = DEFAULT_MATERIAL if material_path is None else load_material(material_path)
    d = build_map.parse_range(diameters, "--diameters")
    p = build_map.parse_range(fills, "--fills")
    workers = workers or default_workers()
    t0 = time.perf_counter()
    with progress.bar(d.size, f"solving {d.size} x {p.size} designs") as bar:
        last = [0]

        def advance(done):
            bar.update(done - last[0])
            last[0] = done

        dmap = build_map.build(material, d, p, workers=workers, progress=advance,
                               scheduler=scheduler, warm_start=not cold_start)
    elapsed_s = time.perf_counter() - t0
    with together(outputs) as tmp:
        map_io.save_map(dmap, tmp["--output"])
        if plot is not None:
            from stitchswitch.reduced.design_space.heatmap import plot_height_map
            plot_height_map(dmap, tmp["--plot"])
    flagged = map_check.report(dmap)
    summary = {"out": str(out), "n_diameters": int(d.size), "n_fills": int(p.size),
               "elapsed_s": round(elapsed_s, 2), "workers": workers,
               "all_converged": bool(dmap.converged.all()),
               "max_residual": float(dmap.residual.max()),
               "material_hash": dmap.material_hash, "flagged": flagged}
    if as_json:
        click.echo(json.dumps(summary))
        return
    click.echo(f"wrote {out}: {d.size} x {p.size} designs in {elapsed_s:.1f} s on {workers} "
               f"worker(s); all certified: {'yes' if summary['all_converged'] else 'NO'} "
               f"(max residual {summary['max_residual']:.1e})")
    if plot is not None:
        click.echo(f"wrote {plot}")
    if not flagged:
        click.echo("smoothness: every interior point within 2 % (or 0.05 mm) of its neighbours' mean")
    else:
        kinds = {}
        for f in flagged:
            kinds.setdefault(f["kind"], []).append(f)
        click.echo(f"smoothness: {len(flagged)} point(s) off their neighbours' mean, explained as:")
        for kind, items in kinds.items():
            where = ", ".join(f"({f['d_mm']:g}, {f['fill']:g})" for f in items[:12])
            more = f" and {len(items) - 12} more" if len(items) > 12 else ""
            click.echo(f"  {kind}: {len(items)} at (d, p) = {where}{more}")
