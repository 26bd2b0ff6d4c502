"""``stitchswitch switch-force``: F(w) of pushing the apex from pop-up to pop-down (shell reference)."""
from __future__ import annotations

import io
import json
import pathlib

import click

from stitchswitch.cli import options
from stitchswitch.files.atomic import atomic_write_bytes, atomic_write_text
from stitchswitch.reduced.model.material_io import load_material
from stitchswitch.reduced.model.params import DEFAULT_MATERIAL, Patch


@click.command("switch-force", cls=options.Command)
@click.option("--diameter", "-d", "diameter_mm", type=options.FINITE_FLOAT, required=True, metavar="MM")
@click.option("--fill", "-p", type=options.FINITE_FLOAT, required=True, metavar="P")
@options.material_opt
@click.option("--steps", type=click.IntRange(min=4, max=400), default=30, show_default=True)
@click.option("--csv", "csv_path", type=click.Path(dir_okay=False, path_type=pathlib.Path), default=None,
              metavar="FILE", help="Write the curve (w_mm, force) as CSV.")
@click.option("--plot", type=click.Path(dir_okay=False, path_type=pathlib.Path), default=None,
              metavar="PNG", help="Plot the curve.")
@options.json_opt
def switch_force(diameter_mm, fill, material_path, steps, csv_path, plot, as_json):
    """Push the apex of the pop-up equilibrium down to w = 0 with the outer edge held, and
    report the reaction force F(w), the switching force (peak |F| before the snap) and the
    energy barrier. Forces are in model units (the material scale is not calibrated to
    newtons): compare designs by their ratios."""
    from stitchswitch.fem_reference.switching import switching_curve

    patch = Patch(diameter_mm, fill)
    material = DEFAULT_MATERIAL if material_path is None else load_material(material_path)
    curve = switching_curve(patch, material, steps=steps)
    if csv_path is not None:
        rows = "\n".join(f"{w:.6f},{f:.9g},{int(c)}" for w, f, c in
                         zip(curve.w_mm, curve.force, curve.converged))
        atomic_write_text(csv_path, "# stitchswitch switch-force, shell reference, force in model "
                          f"units, d_mm={diameter_mm:g}, fill={fill:g}\nw_mm,force,converged\n{rows}\n")
    if plot is not None:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        fig, ax = plt.subplots(figsize=(6, 4), dpi=120)
        ax.plot(curve.w_mm, -curve.force, "o-", ms=3)
        ax.set_xlabel("apex height w (mm)")
        ax.set_ylabel("push force -dE/dw (model units)")
        ax.set_title(f"d = {diameter_mm:g} mm, p = {fill:g}: switching force {curve.switching_force:.3g}")
        ax.invert_xaxis()
        ax.grid(alpha=0.3)
        fig.tight_layout()
        buf = io.BytesIO()
        fig.savefig(buf, format="png")
        plt.close(fig)
        atomic_write_bytes(plot, buf.getvalue())
    out = curve.as_dict()
    if as_json:
        click.echo(json.dumps(out))
        return
    click.echo(f"d = {diameter_mm:g} mm, fill = {fill:g}: pop-up height {out['h_mm']:.2f} mm")
    click.echo(f"switching force {out['switching_force']:.4g} (model units), snap at w = "
               f"{out['w_snap_mm']:.2f} mm, energy barrier {out['energy_barrier']:.4g}")
    if not out["all_converged"]:
        click.echo("warning: some steps did not converge", err=True)
