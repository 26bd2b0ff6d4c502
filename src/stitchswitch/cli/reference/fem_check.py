"""``stitchswitch fem-check``: the reduced model's model error against the shell of revolution."""
from __future__ import annotations

import json
import pathlib

import click

from stitchswitch.cli import options
from stitchswitch.cli.reference.shell_options import shell_options, shell_params
from stitchswitch.files.outdir import check_outdir, previous_output, write_outdir
from stitchswitch.reduced.model.material_io import load_material
from stitchswitch.reduced.model.params import DEFAULT_MATERIAL


def _designs(text: str | None):
    from stitchswitch.fem_reference.model_error.table import DEFAULT_DESIGNS
    from stitchswitch.reduced.model.params import Patch

    if not text:
        return DEFAULT_DESIGNS
    out = []
    for item in text.split(";"):
        try:
            d, p = (float(v) for v in item.split(","))
            Patch(d, p)
        except ValueError:
            raise options.InputError(f"--designs: {item!r} is not D,P (e.g. '40,0.8;90,1')") from None
        except Exception as exc:                       # InvalidInputError: out of range
            raise options.InputError(f"--designs: {item!r}: {exc}") from None
        out.append((d, p))
    return tuple(out)


GENERATOR = "stitchswitch fem-check"


@click.command("fem-check", cls=options.Command)
@click.option("--designs", default=None, metavar="D,P;D,P",
              help="Designs to check (default: d 25, 50, 90 mm x p 0.6, 0.8, 1.0).")
@options.material_opt
@shell_options
@click.option("--report", type=click.Path(file_okay=False, path_type=pathlib.Path), default=None,
              metavar="DIR", help="Also write report.md and report.json into DIR (a new folder, or "
                                  "one this command wrote before).")
@options.json_opt
def fem_check_cmd(designs, material_path, nu, kappa0_per_mm, thickness_mm, elements, report, as_json):
    """Model error of the reduced model (N = 300) against the independent shell of revolution,
    per design and keypoint, with the gap attributed to hoop bending, Poisson coupling, the
    relaxed (tension-field) knit membrane and the natural curvature; exit 1 when a keypoint is
    outside the model-error budget (half the paper's validation error) or a solve is not
    certified."""
    from stitchswitch.fem_reference.model_error import model_error, table_text

    designs = _designs(designs)
    params = shell_params(nu, kappa0_per_mm, thickness_mm, elements)
    material = DEFAULT_MATERIAL if material_path is None else load_material(material_path)
    previous = previous_output(("report.json", "report.md"), GENERATOR)
    if report is not None:                         # refused before any work
        check_outdir(report, previous=previous, what="--report")
    result = model_error(designs, material, params)
    text = table_text(result)
    if report is not None:
        record = {"generator": GENERATOR, **result.as_dict()}
        write_outdir(report, {
            "report.json": (json.dumps(record, indent=1, default=float) + "\n").encode(),
            "report.md": ("# Reduced model against the shell of revolution\n\n```\n" + text
                          + "\n```\n").encode(),
        }, previous=previous)
    click.echo(json.dumps(result.as_dict(), default=float) if as_json else text)
    if not result.all_passed:
        raise SystemExit(1)
