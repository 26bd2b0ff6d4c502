"""``stitchswitch validate``: compare the model with measured keypoints and write a report."""
from __future__ import annotations

import json
import pathlib

import click

from stitchswitch.cli import options
from stitchswitch.cli.output import key_value_table
from stitchswitch.reduced.model.material_io import load_material
from stitchswitch.reduced.model.params import DEFAULT_MATERIAL
from stitchswitch.validation.measured import QUANTITIES, load_measurements
from stitchswitch.validation.metrics import PAPER_TABLE1
from stitchswitch.validation.report import check_report_dir, write_report


@click.command(cls=options.Command)
@click.argument("data_path", metavar="DATA.csv", type=click.Path(path_type=pathlib.Path))
@options.material_opt
@click.option("--report", "report_dir", required=True, metavar="DIR",
              type=click.Path(path_type=pathlib.Path),
              help="Directory to write the report into (new, empty, or a previous report, "
                   "which is replaced).")
@options.json_opt
def validate(data_path, material_path, report_dir, as_json):
    """Predict every patch of DATA.csv and compare with its measured keypoints.

    DATA.csv has one row per fabricated patch (columns d_mm, fill, h_mm, r_a_mm, z_a_mm,
    r_b_mm, z_b_mm, split; see docs/data.md). Prints percentage error and MAE per quantity for
    the train and val rows, as in the paper's Table 1, and writes report.md, report.html,
    report.json and PNG figures into DIR. A material other than the default builds its design
    map first (about 25 s, cached).
    """
    data = load_measurements(data_path)
    material = DEFAULT_MATERIAL if material_path is None else load_material(material_path)
    check_report_dir(report_dir)
    rep = write_report(data, material, report_dir,
                       material_label=str(material_path) if material_path else "default")
    click.echo(json.dumps(rep) if as_json else table(rep, report_dir))


def table(rep: dict, report_dir) -> str:
    """Table-1-style summary, then provenance and where the report went."""
    d = rep["data"]
    fmt = lambda v, n: "n/a" if v is None else f"{v:.{n}f}"  # noqa: E731
    head = ("quantity", "err% train", "err% val", "MAE train", "MAE val", "paper err%", "paper MAE")
    rows = [head]
    for q in QUANTITIES:
        t, v, pt, pv = rep["train"][q], rep["val"][q], PAPER_TABLE1["train"][q], PAPER_TABLE1["val"][q]
        rows.append((q, fmt(t["pct_error"], 1), fmt(v["pct_error"], 1), fmt(t["mae_mm"], 2),
                     fmt(v["mae_mm"], 2), f"{pt['pct_error']:.1f}/{pv['pct_error']:.1f}",
                     f"{pt['mae_mm']:.2f}/{pv['mae_mm']:.2f}"))
    widths = [max(len(r[k]) for r in rows) for k in range(len(head))]
    lines = ["  ".join(c.ljust(w) if k == 0 else c.rjust(w) for k, (c, w) in
                       enumerate(zip(r, widths))).rstrip() for r in rows]
    bad = rep["not_converged"]
    skips = [f"{s} {q} ({rep[s][q]['n_pct_skipped']})" for s in ("train", "val")
             for q in QUANTITIES if rep[s][q]["n_pct_skipped"]]
    lines += ["",
              "MAE in mm; error% = mean |pred - meas| / |meas| (paper: its Table 1, train/val)"]
    if skips:
        lines.append("rows measured as 0, left out of error%: " + ", ".join(skips))
    facts = [
        ("data", f"{d['path']}: {d['n_train']} train, {d['n_val']} val rows"),
        ("source", d["source"] + ("  (SYNTHETIC, not measured)" if d["synthetic"] else "")),
        ("material", f"{rep['material']['label']} (sha256 {rep['material']['sha256'][:12]})"),
        ("solves", "all converged" if not bad else
                   f"{len(bad)} did not converge (lines {', '.join(map(str, bad))})"),
        ("report", f"{pathlib.Path(report_dir) / 'report.html'} (also report.md, report.json, PNGs)")]
    return "\n".join(lines + [key_value_table(facts)])
