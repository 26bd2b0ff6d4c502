"""``stitchswitch bistability-map``: bistable / spring-back / flat regions over (d, p)."""
from __future__ import annotations

import json

import click

from stitchswitch.cli import options
from stitchswitch.cli.reference.shell_options import shell_options, shell_params
from stitchswitch.files.atomic import atomic_write_bytes
from stitchswitch.files.outputs import together
from stitchswitch.reduced.model.material_io import load_material
from stitchswitch.reduced.model.params import DEFAULT_MATERIAL


def _values(text: str, name: str, kind):
    try:
        vals = [float(v) for v in text.split(",")]
    except ValueError:
        raise options.InputError(f"{name}: {text!r} is not a comma-separated list of numbers") from None
    try:
        for v in vals:
            kind(v)
    except Exception as exc:
        raise options.InputError(f"{name}: {text!r}: {exc}") from None
    return vals


@click.command("bistability-map", cls=options.Command)
@click.option("--diameters", default="20,30,40,50,60,70,80,90", show_default=True, metavar="MM,MM",
              help="Patch diameters (mm).")
@click.option("--fills", default="0.6,0.7,0.8,0.9,1.0", show_default=True, metavar="P,P",
              help="Fill fractions.")
@options.material_opt
@shell_options
@click.option("--png", type=options.OutputFile((".png",)), default=None,
              metavar="FILE", help="Draw the regions.")
@options.json_opt
def bistability_map_cmd(diameters, fills, material_path, nu, kappa0_per_mm, thickness_mm, elements,
                        png, as_json):
    """Which designs are bistable (the inverted state is a strict local minimum without load),
    which spring back and which stay flat, over a grid of (d, p), for a natural curvature of
    the embroidered layer (--kappa0)."""
    from stitchswitch.fem_reference.snap.regions import bistability_map, map_png, text_grid
    from stitchswitch.reduced.model.params import Patch

    ds = _values(diameters, "--diameters", lambda d: Patch(d, 1.0))
    ps = _values(fills, "--fills", lambda p: Patch(50.0, p))
    if kappa0_per_mm < 0:
        raise options.InputError(f"--kappa0: {kappa0_per_mm:g} < 0; the map of -kappa0 is the same "
                                 "with the two states swapped")
    material = DEFAULT_MATERIAL if material_path is None else load_material(material_path)
    result = bistability_map(ds, ps, material, shell_params(nu, kappa0_per_mm, thickness_mm, elements))
    if png is not None:
        with together({"--png": png}) as tmp:
            atomic_write_bytes(tmp["--png"], map_png(result))
    if as_json:
        click.echo(json.dumps({**result.as_dict(), "counts": result.counts()}))
    else:
        click.echo(f"natural curvature {kappa0_per_mm:g} /mm (shell of revolution, held in its frame)")
        click.echo(text_grid(result))
