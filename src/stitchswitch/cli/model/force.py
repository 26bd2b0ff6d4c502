"""``stitchswitch force``: predicted switching force of one patch (paper, Appendix B)."""
from __future__ import annotations

import json
import logging
import pathlib

import click

from stitchswitch.cli import options
from stitchswitch.cli.output import key_value_table
from stitchswitch.files.jsonsafe import json_safe
from stitchswitch.reduced.design_space.force_model import (
    ForceFit,
    default_force_fit,
    fit_force_model,
    load_force_csv,
)
from stitchswitch.reduced.model.params import DIAMETER_RANGE_MM, Patch

log = logging.getLogger(__name__)


@click.command(cls=options.Command)
@click.option("--diameter", "-d", "diameter_mm", type=options.FINITE_FLOAT, required=True,
              metavar="MM", help="Patch diameter in mm, measured on the pre-stretched fabric; "
              f"range [{DIAMETER_RANGE_MM[0]:g}, {DIAMETER_RANGE_MM[1]:g}].")
@click.option("--fill", "-p", type=options.FINITE_FLOAT, required=True, metavar="P",
              help="Fill fraction of the embroidery, in (0, 1].")
@click.option("--data", "data_path", type=click.Path(path_type=pathlib.Path), default=None,
              metavar="CSV", help="Force table to fit (columns d_mm, fill, force_N, split; "
              "see docs/force.md). Default: the shipped SYNTHETIC table.")
@options.json_opt
def force(diameter_mm, fill, data_path, as_json):
    """Switching force of a patch from the second-order polynomial in (d, p).

    The polynomial is fitted to the shipped synthetic force table (not measured data; the
    output says so) or to --data. Designs outside the fitted designs' range get a warning on
    stderr and are still answered.
    """
    patch = Patch(diameter_mm, fill)
    fit = default_force_fit() if data_path is None else fit_force_model(*load_force_csv(data_path))
    force_N = float(fit.model.predict(patch.diameter_mm, patch.fill))
    extrapolated = fit.extrapolates(patch.diameter_mm, patch.fill)
    if extrapolated:
        log.warning("d = %g mm, fill = %g is outside the fitted designs (d %g-%g mm, fill %g-%g): "
                    "the force is extrapolated%s", patch.diameter_mm, patch.fill,
                    *fit.d_range_mm, *fit.fill_range,
                    " (and negative: the polynomial means nothing there)" if force_N < 0 else "")
    if as_json:
        out = {"force_N": force_N, "d_mm": patch.diameter_mm, "fill": patch.fill,
               "extrapolated": extrapolated, **fit.as_dict()}
        click.echo(json.dumps(json_safe(out)))
    else:
        click.echo(table(patch, force_N, fit))


def table(patch: Patch, force_N: float, fit: ForceFit) -> str:
    """The human-readable summary: one aligned ``name  value`` row per quantity."""
    rows = [
        ("design", f"d = {patch.diameter_mm:g} mm, fill = {patch.fill:g}"),
        ("force", f"{force_N:.3f} N"),
        ("R^2", f"{fit.r2_train:.3f} train ({fit.n_train}), {fit.r2_val:.3f} val ({fit.n_val})"),
        ("val MAE", f"{fit.mae_val_N:.3f} N"),
        ("data", fit.source),
    ]
    return key_value_table(rows)
