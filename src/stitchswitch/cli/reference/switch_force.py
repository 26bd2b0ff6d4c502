"""``stitchswitch switch-force``: snap-through by the contact plate (shell of revolution): the
force-displacement curve, the switching force in newtons, the energy barrier, both states, and
whether the patch is bistable or springs back."""
from __future__ import annotations

import json
import logging

import click

from stitchswitch.cli import options
from stitchswitch.cli.reference.shell_options import shell_options, shell_params
from stitchswitch.errors import StitchSwitchError
from stitchswitch.files.outputs import check_distinct, together
from stitchswitch.reduced.model.material_io import load_material
from stitchswitch.reduced.model.params import DEFAULT_MATERIAL, Patch

STIFFNESS = options.BoundedFloat(0.0, 1e5, low_open=True)


@click.command("switch-force", cls=options.Command)
@click.option("--diameter", "-d", "diameter_mm", type=options.FINITE_FLOAT, required=True, metavar="MM",
              help="Patch diameter on the pre-stretched fabric (mm).")
@click.option("--fill", "-p", type=options.FINITE_FLOAT, required=True, metavar="P",
              help="Embroidery fill fraction, in (0, 1].")
@options.material_opt
@shell_options
@click.option("--knit-stiffness", "knit_stiffness_n_per_m", type=STIFFNESS, default=200.0,
              show_default=True, metavar="N_PER_M",
              help="Tensile membrane stiffness of the bare knit (N/m): the force scale "
              "(docs/force.md).")
@click.option("--steps", type=click.IntRange(min=6, max=400), default=24, show_default=True,
              metavar="N", help="Plate steps from the apex height h down to -1.5 h (the most it travels).")
@click.option("--csv", "csv_path", type=options.OutputFile((".csv",)), default=None,
              metavar="FILE", help="Write the curve (w_mm, force_N) as CSV.")
@click.option("--plot", type=options.OutputFile((".png",)), default=None,
              metavar="PNG", help="Plot the curve (together with --csv: both or neither).")
@options.json_opt
def switch_force(diameter_mm, fill, material_path, nu, kappa0_per_mm, thickness_mm, elements,
                 knit_stiffness_n_per_m, steps, csv_path, plot, as_json):
    """Press the pop-up patch with a rigid contact plate (held in its frame, as in the paper's
    experiment) until it switches, and report the switching force (N), the energy barrier (mJ),
    both stable states and whether the design is bistable or springs back."""
    from dataclasses import replace

    from stitchswitch.fem_reference.snap.path import switching_path
    from stitchswitch.fem_reference.snap.path_csv import write_curve_csv
    from stitchswitch.fem_reference.snap.path_plot import write_curve_png
    from stitchswitch.fem_reference.snap.states import bistability

    outputs = {"--csv": csv_path, "--plot": plot}
    check_distinct(outputs)
    patch = Patch(diameter_mm, fill)
    params = replace(shell_params(nu, kappa0_per_mm, thickness_mm, elements),
                     knit_stiffness_n_per_m=knit_stiffness_n_per_m)
    material = DEFAULT_MATERIAL if material_path is None else load_material(material_path)
    try:
        curve = switching_path(patch, material, params, steps=steps)
    except StitchSwitchError as exc:          # a flat design: nothing to switch (exit 1)
        raise click.ClickException(str(exc)) from None
    out = curve.as_dict()
    # bistable: the inverted state is a strict local minimum without load (whether or not this
    # axisymmetric path reaches it)
    out["verdict"] = bistability(patch, material, params).verdict
    out["knit_stiffness_n_per_m"] = knit_stiffness_n_per_m
    with together(outputs) as tmp:
        if tmp.get("--csv") is not None:
            write_curve_csv(tmp["--csv"], curve, knit_stiffness_n_per_m)
        if tmp.get("--plot") is not None:
            write_curve_png(tmp["--plot"], curve, out["verdict"])
    if as_json:
        click.echo(json.dumps(out))
        return
    up, down = out["popup"], out["switched"]
    click.echo(f"d = {diameter_mm:g} mm, fill = {fill:g}: {out['verdict']} "
               f"(plate radius {curve.plate_radius_mm:.1f} mm, knit stiffness "
               f"{knit_stiffness_n_per_m:g} N/m)")
    click.echo(f"switching force {out['switching_force_n']:.4g} N at plate height "
               f"{out['w_switch_mm']:.2f} mm, energy barrier {out['energy_barrier_mj']:.4g} mJ")
    click.echo(f"pop-up state:   h {up['h_mm']:.2f} mm, r_a {up['r_a_mm']:.2f}, z_a {up['z_a_mm']:.2f}, "
               f"energy {up['energy_mj']:.4g} mJ")
    click.echo(f"after the path: apex {down['apex_mm']:.2f} mm, r_a {down['r_a_mm']:.2f}, "
               f"z_a {down['z_a_mm']:.2f}, energy {down['energy_mj']:.4g} mJ "
               f"({'the inverted state' if curve.inverted else 'back on the pop-up side'})")
    log = logging.getLogger(__name__)
    if not curve.limit_point:
        log.warning("the force rose to the end of the plate's travel (no limit point on this "
                    "path); the switching force printed is the last force")
    if not out["all_converged"]:
        log.warning("some plate steps did not converge")
