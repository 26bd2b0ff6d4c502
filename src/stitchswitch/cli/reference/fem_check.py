"""``stitchswitch fem-check``: the reduced model (N = 75 ... 600) against the shell reference."""
from __future__ import annotations

import json
import pathlib

import click

from stitchswitch.cli import options
from stitchswitch.cli.reference.shell_options import shell_options
from stitchswitch.fem_reference.check import DEFAULT_DESIGNS, fem_check, table
from stitchswitch.files.atomic import atomic_write_text
from stitchswitch.reduced.model.material_io import load_material
from stitchswitch.reduced.model.params import DEFAULT_MATERIAL


def _designs(text: str | None):
    if not text:
        return DEFAULT_DESIGNS
    out = []
    for item in text.split(";"):
        try:
            d, p = (float(v) for v in item.split(","))
        except ValueError:
            raise options.InputError(f"--designs: {item!r} is not D,P (e.g. '40,0.8;90,1')") from None
        out.append((d, p))
    return tuple(out)


@click.command("fem-check", cls=options.Command)
@click.option("--designs", default=None, metavar="D,P;D,P",
              help="Designs to check (default: d 25, 50, 90 mm x p 0.6, 0.8, 1.0).")
@options.material_opt
@shell_options
@click.option("--report", type=click.Path(file_okay=False, path_type=pathlib.Path), default=None,
              metavar="DIR", help="Also write report.md and report.json into DIR.")
@options.json_opt
def fem_check_cmd(designs, material_path, hoop_bending, poisson, start, report, as_json):
    """Relative difference of every keypoint between the reduced model (N = 75, 150, 300, 600)
    and the scikit-fem shell reference, per design; exit 1 if the N = 300 targets (h within
    5 %, r_a within 3 %) are missed."""
    from stitchswitch.reduced.model.params import Patch

    material = DEFAULT_MATERIAL if material_path is None else load_material(material_path)
    designs = _designs(designs)
    for d, p in designs:
        Patch(d, p)
    result = fem_check(designs, material, hoop_bending=hoop_bending, poisson=poisson, start=start)
    text = table(result)
    if report is not None:
        report.mkdir(parents=True, exist_ok=True)
        atomic_write_text(report / "report.json", json.dumps(result.as_dict(), indent=1, default=float)
                          + "\n")
        atomic_write_text(report / "report.md", "# Reduced model against the shell reference\n\n"
                          "```\n" + text + "\n```\n")
    click.echo(json.dumps(result.as_dict(), default=float) if as_json else text)
    if not result.all_met:
        raise SystemExit(1)
