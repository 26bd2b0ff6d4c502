"""``stitchswitch sensitivity``: the elasticity of each keypoint to each material parameter."""
from __future__ import annotations

import json
import math
import time

import click

from stitchswitch.cli import options, progress
from stitchswitch.cli.output import key_value_table
from stitchswitch.executor import default_workers
from stitchswitch.files.jsonsafe import json_safe
from stitchswitch.reduced.calibration import sensitivity as sens
from stitchswitch.reduced.model.material_io import load_material, material_hash
from stitchswitch.reduced.model.params import DEFAULT_MATERIAL

HEADER = ("parameter", "keypoint", "|E| median", "|E| max", "|dq/dlog| median mm",
          "|dq/dlog| max mm", "flagged")


@click.command(cls=options.Command)
@options.material_opt
@click.option("--step", type=options.FINITE_FLOAT, default=sens.DEFAULT_STEP, show_default=True,
              metavar="S", help="Step in log(parameter): each parameter is scaled by exp(+-S).")
@click.option("--all", "include_numerical", is_flag=True,
              help="Also the numerical parameters (" + ", ".join(sens.NUMERICAL) + ").")
@click.option("--workers", type=click.IntRange(min=1), default=None, metavar="N",
              help="Worker processes (default: one per core).")
@options.json_opt
def sensitivity(material_path, step, include_numerical, workers, as_json):
    """Elasticity (dq/q)/(dtheta/theta) of h, r_a, z_a, r_b, z_b to each material parameter.

    Central differences in log(parameter) at the paper's 25 calibration designs; per parameter
    and keypoint the median and max over the designs of |elasticity| and of |dq/dlog theta|
    (mm), and how many designs were flagged (not certified or not smooth) and left out.
    """
    material = DEFAULT_MATERIAL if material_path is None else load_material(material_path)
    step = sens.check_step(step)
    parameters = sens.parameter_names(include_numerical)
    workers = workers or default_workers()
    designs = sens.CALIBRATION_DESIGNS
    t0 = time.perf_counter()
    with progress.bar(len(designs), f"{len(designs)} designs x {len(parameters)} parameters") as bar:
        result = sens.sensitivity(material, designs, step, parameters=parameters,
                                  workers=workers, progress=lambda done: bar.update(1))
    elapsed_s = time.perf_counter() - t0
    if as_json:
        out = {**result.as_dict(), "material_hash": material_hash(material),
               "elapsed_s": round(elapsed_s, 2), "workers": workers}
        click.echo(json.dumps(json_safe(out), allow_nan=False))
        return
    click.echo(key_value_table([
        ("material", f"{material_path or 'default'} (sha256 {material_hash(material)[:12]})"),
        ("designs", f"{len(designs)} (d x p), step exp(+-{step:g})"),
        ("solves", f"{result.n_solves} in {elapsed_s:.1f} s on {workers} worker(s)"),
    ]))
    click.echo("")
    click.echo(table(result))


def _num(value: float, fmt: str) -> str:
    return "-" if not math.isfinite(value) else format(value, fmt)


def table(result: sens.Sensitivity) -> str:
    """One aligned row per (parameter, keypoint); "-" where no design gives a value."""
    lines = [HEADER] + [
        (r.parameter, r.keypoint, _num(r.median_abs_elasticity, ".3f"),
         _num(r.max_abs_elasticity, ".3f"), _num(r.median_abs_dq_dlog_mm, ".3f"),
         _num(r.max_abs_dq_dlog_mm, ".3f"), f"{r.n_flagged}/{r.n_designs}")
        for r in result.rows]
    widths = [max(len(row[i]) for row in lines) for i in range(len(HEADER))]
    return "\n".join("  ".join(c.ljust(w) if i < 2 else c.rjust(w)
                               for i, (c, w) in enumerate(zip(row, widths))).rstrip()
                     for row in lines)
