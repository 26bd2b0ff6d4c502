"""Validation report: the model's predictions against measured keypoints (paper, 5.1, Table 1).

``predict`` solves every row's design with the certified ``solve`` (Newton, cold start, the
same deterministic solve as ``stitchswitch simulate``); identical designs are solved once. A
solve that does not converge is kept (the paper's own predictions are uncertified Adam
results) and recorded: ``Predictions.converged``, the ``converged`` field of each row in
report.json, a list in the report and a marker in the plots.

``write_report`` writes into one directory::

    report.md  report.html  report.json  scatter_<q>.png (q in h, r_a, z_a, r_b, z_b)
    all_quantities.png  height_map.png

report.html is self-contained (``files.html_page``: inline CSS, the PNGs as base64 data URIs,
no external resources). report.json holds the metrics under ``train``/``val`` (see ``metrics``), the
paper's Table 1 under ``paper_table1``, the data's provenance and sha256, the material's
hash and every row's prediction. No timestamps: equal inputs give an equal report.json.

The directory is written as a whole: the report is built in a temporary directory next to it
and renamed into place, so on any error nothing is left behind. An existing target must be
empty or a previous report of this tool (its report.json says ``"generator": "stitchswitch
validate"`` and it holds no other files); a previous report is then replaced (moved aside,
the new one renamed in, the old one deleted). Anything else is refused with
``InvalidInputError`` before any work is done.

The height map is ``map_cache.map_for(material, coarse=True)``: the shipped map for the default
material, a cached full map for any other, else a coarse grid (d every 5 mm, p every 0.05) built
in a few seconds and cached.
"""
from __future__ import annotations

import json
import logging
import math
import os
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from stitchswitch import __version__
from stitchswitch.files.figures import plot_bytes
from stitchswitch.files.html_page import Figure, Gallery, Paragraph, Section, Table, code, inline, page, strong
from stitchswitch.files.jsonsafe import json_safe
from stitchswitch.files.outdir import building, check_outdir, previous_output
from stitchswitch.reduced.model.material_io import material_hash
from stitchswitch.reduced.model.params import Material, Patch
from stitchswitch.validation.measured import QUANTITIES, SPLITS, MeasuredData
from stitchswitch.validation.metrics import PAPER_TABLE1, table1

__all__ = ["Predictions", "predict", "write_report", "check_report_dir", "provenance_statement",
           "REPORT_FILES", "GENERATOR"]

log = logging.getLogger(__name__)

GENERATOR = "stitchswitch validate"
FIGURES = tuple(f"scatter_{q}.png" for q in QUANTITIES) + ("all_quantities.png", "height_map.png")
REPORT_FILES = ("report.md", "report.html", "report.json") + FIGURES
COLORS = {"train": "tab:blue", "val": "tab:orange"}
LABELS = {"h": "peak height h", "r_a": "boundary radius r_a", "z_a": "boundary height z_a",
          "r_b": "radius r_b at b", "z_b": "height z_b at b"}
PCT_DEFINITION = ("mean over the rows of 100 |predicted - measured| / |measured|; rows measured "
                  "as exactly 0 are left out of the percentage only (counted as skipped)")
MAE_DEFINITION = "mean over the rows of |predicted - measured|, in mm"


@dataclass(frozen=True)
class Predictions:
    """Model keypoints for every row of a ``MeasuredData`` (same order): ``values`` (n, 5) in
    mm, columns h, r_a, z_a, r_b, z_b; the certificate of each solve (``converged``,
    ``residual``) and the rule that placed b (``b_rule``)."""

    values: np.ndarray
    converged: np.ndarray
    residual: np.ndarray
    b_rule: tuple

    @property
    def all_converged(self) -> bool:
        return bool(np.all(self.converged))


def predict(data: MeasuredData, material: Material) -> Predictions:
    """Solve each row's design (d, p) with ``solve``; identical designs are solved once."""
    from stitchswitch.reduced.solvers.solve import solve

    cache = {}
    for r in data.rows:
        key = (r.diameter_mm, r.fill)
        if key not in cache:
            sol = solve(Patch(r.diameter_mm, r.fill), material)
            kp = sol.keypoints
            cache[key] = ((kp.h_mm, kp.r_a_mm, kp.z_a_mm, kp.r_b_mm, kp.z_b_mm),
                          sol.converged, sol.residual, kp.b_rule)
    rows = [cache[(r.diameter_mm, r.fill)] for r in data.rows]
    values = np.array([v for v, *_ in rows], dtype=float).reshape(len(rows), len(QUANTITIES))
    return Predictions(values=values, converged=np.array([c for _, c, _, _ in rows], bool),
                       residual=np.array([res for _, _, res, _ in rows], float),
                       b_rule=tuple(b for *_, b in rows))


# ----------------------------------------------------------------------------- target directory

def check_report_dir(outdir) -> bool:
    """Raise ``InvalidInputError`` unless ``outdir`` can take a report; True if it holds a
    previous report that will be replaced."""
    return check_outdir(outdir, previous=_PREVIOUS, what="report directory")


_PREVIOUS = previous_output(REPORT_FILES, GENERATOR)


# ----------------------------------------------------------------------------- figures

def _pyplot():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def _scatter(ax, k: int, q: str, measured, pred: Predictions, splits, show_legend=True) -> None:
    m, y = measured[:, k], pred.values[:, k]
    for s in SPLITS:
        sel = splits == s
        ax.scatter(m[sel], y[sel], s=26, c=COLORS[s], edgecolors="black", linewidths=0.4,
                   label=f"{s} ({int(sel.sum())})", zorder=3)
    bad = ~pred.converged
    if np.any(bad):
        ax.scatter(m[bad], y[bad], s=60, facecolors="none", edgecolors="red", linewidths=1.0,
                   label=f"solve not converged ({int(bad.sum())})", zorder=4)
    lo = min(float(m.min()), float(y.min()))
    hi = max(float(m.max()), float(y.max()))
    pad = 0.06 * (hi - lo) if hi > lo else 1.0
    lo, hi = lo - pad, hi + pad
    ax.plot([lo, hi], [lo, hi], color="0.4", lw=0.8, ls="--", zorder=1, label="y = x")
    ax.set_xlim(lo, hi)
    ax.set_ylim(lo, hi)
    ax.set_aspect("equal", adjustable="box")
    ax.set_xlabel(f"measured {q} (mm)")
    ax.set_ylabel(f"predicted {q} (mm)")
    ax.set_title(LABELS[q], fontsize=10)
    ax.grid(True, lw=0.3, alpha=0.5)
    if show_legend:
        ax.legend(fontsize=7, loc="upper left", framealpha=0.85)


def _png(fig) -> bytes:
    return plot_bytes(fig)


def _figures(data: MeasuredData, pred: Predictions, material: Material, tmp: Path) -> None:
    from stitchswitch.reduced.design_space.cache import map_for
    from stitchswitch.reduced.design_space.heatmap import plot_height_map

    plt = _pyplot()
    measured = data.keypoints()
    splits = np.array([r.split for r in data.rows])
    for k, q in enumerate(QUANTITIES):
        fig, ax = plt.subplots(figsize=(4.4, 4.4), dpi=120)
        _scatter(ax, k, q, measured, pred, splits)
        fig.tight_layout()
        (tmp / f"scatter_{q}.png").write_bytes(_png(fig))
    fig, axes = plt.subplots(2, 3, figsize=(12.0, 8.8), dpi=110)
    for k, q in enumerate(QUANTITIES):
        _scatter(axes.flat[k], k, q, measured, pred, splits, show_legend=False)
    handles, labels = axes.flat[0].get_legend_handles_labels()
    axes.flat[5].axis("off")
    axes.flat[5].legend(handles, labels, loc="center", fontsize=10, frameon=False,
                        title="measured vs. predicted")
    fig.suptitle("Actual vs. predicted keypoints (mm)", fontsize=12)
    fig.tight_layout(h_pad=2.0)
    (tmp / "all_quantities.png").write_bytes(_png(fig))
    dmap = map_for(material, coarse=True)
    points = {f"{s} data ({len(data.split(s))})": (data.array("diameter_mm", s), data.array("fill", s))
              for s in SPLITS}
    plot_height_map(dmap, tmp / "height_map.png", points=points,
                    title=f"Predicted h(d, p) with the data, material {dmap.material_hash[:10]}")


# ----------------------------------------------------------------------------- report text

def _fmt(v, digits: int) -> str:
    return "n/a" if v is None or (isinstance(v, float) and not math.isfinite(v)) else f"{v:.{digits}f}"


def provenance_statement(data: MeasuredData) -> str:
    """One sentence on what the data are, from the file's ``# source:`` line."""
    if data.synthetic:
        return ("SYNTHETIC DATA: the data file's source line says synthetic, so these rows are "
                "not measurements of fabricated patches and the agreement below says nothing "
                "about real textiles.")
    if data.source == "unspecified":
        return ("Unspecified provenance: the data file has no '# source:' line, so it is not "
                "known whether these rows are measurements.")
    return f"The data file's source line does not say synthetic: {data.source}"


def _report_dict(data: MeasuredData, pred: Predictions, material: Material, label: str) -> dict:
    rows = []
    for i, r in enumerate(data.rows):
        rows.append({
            "line": r.line, "sample_id": r.sample_id, "split": r.split, "d_mm": r.diameter_mm,
            "fill": r.fill,
            "measured": {q: getattr(r, f"{q}_mm") for q in QUANTITIES},
            "predicted": {q: float(pred.values[i, k]) for k, q in enumerate(QUANTITIES)},
            "converged": bool(pred.converged[i]), "residual": float(pred.residual[i]),
            "b_rule": pred.b_rule[i]})
    metrics = table1(data, pred.values)
    return json_safe({
        "generator": GENERATOR, "version": __version__,
        "data": {"path": data.path, "source": data.source, "synthetic": data.synthetic,
                 "provenance": provenance_statement(data), "sha256": data.sha256,
                 "n_train": len(data.split("train")), "n_val": len(data.split("val"))},
        "material": {"label": label, "sha256": material_hash(material)},
        "solver": "newton (certified, cold start)",
        "definitions": {"pct_error": PCT_DEFINITION, "mae_mm": MAE_DEFINITION},
        "train": metrics["train"], "val": metrics["val"],
        "paper_table1": {**PAPER_TABLE1, "note": "quoted from the paper (Table 1): its own 25 "
                         "train and 28 validation patches, not computed here"},
        "not_converged": [r["line"] for r in rows if not r["converged"]],
        "rows": rows,
        "files": list(REPORT_FILES),
    })


def _metric_rows(rep: dict) -> list[list[str]]:
    out = []
    for q in QUANTITIES:
        t, v = rep["train"][q], rep["val"][q]
        pt, pv = PAPER_TABLE1["train"][q], PAPER_TABLE1["val"][q]
        out.append([q, _fmt(t["pct_error"], 1), _fmt(v["pct_error"], 1), _fmt(t["mae_mm"], 2),
                    _fmt(v["mae_mm"], 2), f"{pt['pct_error']:.1f} / {pv['pct_error']:.1f}",
                    f"{pt['mae_mm']:.2f} / {pv['mae_mm']:.2f}"])
    return out


METRIC_HEADER = ["quantity", "error % train", "error % val", "MAE train (mm)", "MAE val (mm)",
                 "paper error % train / val", "paper MAE train / val (mm)"]
ROW_HEADER = ["line", "sample", "split", "d (mm)", "fill"] + \
    [f"{q} meas / pred" for q in QUANTITIES] + ["converged"]


def _row_cells(r: dict) -> list[str]:
    return [str(r["line"]), r["sample_id"] or "-", r["split"], f"{r['d_mm']:g}", f"{r['fill']:g}"] + \
        [f"{r['measured'][q]:.2f} / {r['predicted'][q]:.2f}" for q in QUANTITIES] + \
        ["yes" if r["converged"] else "NO"]


def _skips(rep: dict) -> list[str]:
    return [f"{s} {q}: {rep[s][q]['n_pct_skipped']} row(s) measured as 0"
            for s in SPLITS for q in QUANTITIES if rep[s][q]["n_pct_skipped"]]


def _markdown(rep: dict) -> str:
    d, m = rep["data"], rep["material"]
    md = lambda cells: "| " + " | ".join(c.replace("|", "\\|") for c in cells) + " |"  # noqa: E731
    lines = ["# Model validation against measured keypoints", "",
             f"> **{d['provenance']}**", "",
             f"- data: `{d['path']}` (sha256 `{d['sha256']}`)",
             f"- source line: {d['source']}",
             f"- rows: {d['n_train']} train, {d['n_val']} val",
             f"- material: {m['label']} (sha256 `{m['sha256']}`)",
             f"- predictions: {rep['solver']}; "
             + ("every solve converged" if not rep["not_converged"] else
                f"**{len(rep['not_converged'])} solve(s) did not converge** (lines "
                f"{', '.join(map(str, rep['not_converged']))}); they are included"), "",
             "## Agreement per quantity (as in the paper's Table 1)", "",
             md(METRIC_HEADER), md(["---"] * len(METRIC_HEADER))]
    lines += [md(r) for r in _metric_rows(rep)]
    lines += ["", f"Error %: {PCT_DEFINITION}. MAE: {MAE_DEFINITION}. The paper's columns are "
              "quoted from its Table 1 (its own patches), for comparison only."]
    if _skips(rep):
        lines += ["", "Left out of the error %: " + "; ".join(_skips(rep)) + "."]
    lines += ["", "## Actual vs. predicted (as in the paper's Fig. 4 right and Fig. 8)", "",
              "![all quantities](all_quantities.png)", "",
              "Per quantity: " + ", ".join(f"[{q}](scatter_{q}.png)" for q in QUANTITIES) + ".",
              "", "## The data on the predicted height map h(d, p)", "",
              "![height map](height_map.png)", "", "## Rows", "",
              md(ROW_HEADER), md(["---"] * len(ROW_HEADER))]
    lines += [md(_row_cells(r)) for r in rep["rows"]]
    lines += ["", f"Generated by `{rep['generator']}` {rep['version']}; the numbers are in "
              "report.json.", ""]
    return "\n".join(lines)


def _html(rep: dict, images: dict[str, bytes]) -> str:
    d, m = rep["data"], rep["material"]
    kind = "synthetic" if d["synthetic"] else "unspecified" if d["source"] == "unspecified" else "measured"
    conv = ("every solve converged" if not rep["not_converged"] else
            inline(strong(f"{len(rep['not_converged'])} solve(s) did not converge"), " (lines "
                   f"{', '.join(map(str, rep['not_converged']))}); they are included and circled red"))
    meta = (("data file", code(d["path"])), ("source line", d["source"]),
            ("data sha256", code(d["sha256"])), ("rows", f"{d['n_train']} train, {d['n_val']} val"),
            ("material", m["label"]), ("material sha256", code(m["sha256"])),
            ("predictions", inline(f"{rep['solver']}; ", conv)))
    skips = _skips(rep)
    paper = tuple((j, "paper") for j, h in enumerate(METRIC_HEADER) if h.startswith("paper"))
    blocks = (
        Paragraph(d["provenance"], cls=f"banner {kind}"),
        Table(meta, keys=True),
        Section("Agreement per quantity (as in the paper's Table 1)", (
            Table(tuple(_metric_rows(rep)), head=tuple(METRIC_HEADER), cls="numbers",
                  column_classes=paper, scroll=True),
            Paragraph(f"Error %: {PCT_DEFINITION}. MAE: {MAE_DEFINITION}. The grey columns are "
                      "quoted from the paper's Table 1 (its own fabricated patches), for "
                      "comparison only."
                      + (" Left out of the error %: " + "; ".join(skips) + "." if skips else ""),
                      cls="note"))),
        Section("Actual vs. predicted (as in the paper's Fig. 4 right and Fig. 8)", (
            Gallery(tuple(Figure(images[f"scatter_{q}.png"], f"measured vs. predicted {LABELS[q]}")
                          for q in QUANTITIES)),)),
        Section("The data on the predicted height map h(d, p)", (
            Figure(images["height_map.png"], "height map with the data points", cls="wide"),)),
        Section("Rows", (
            Table(tuple(_row_cells(r) for r in rep["rows"]), head=tuple(ROW_HEADER),
                  cls="numbers small", scroll=True,
                  row_classes=tuple(None if r["converged"] else "bad" for r in rep["rows"])),)),
    )
    return page(f"stitchswitch validation: {os.path.basename(d['path'])}", blocks,
                heading="Model validation against measured keypoints",
                footer=f"Generated by {rep['generator']} {rep['version']}. The numbers are in "
                       "report.json; the figures are also saved as PNG files next to this page.")


# ----------------------------------------------------------------------------- entry point

def write_report(data: MeasuredData, material: Material, outdir, material_label: str = "default") -> dict:
    """Predict every row, compare, and write the report directory ``outdir`` as a whole (see
    the module docstring). Returns the content of report.json."""
    out = Path(outdir)
    check_report_dir(out)
    pred = predict(data, material)
    if not pred.all_converged:
        log.warning("%d of %d solves did not converge (lines %s); their predictions are included "
                    "and marked", int((~pred.converged).sum()), len(data.rows),
                    ", ".join(str(r.line) for r, c in zip(data.rows, pred.converged) if not c))
    rep = _report_dict(data, pred, material, material_label)
    with building(out, previous=_PREVIOUS, what="report directory") as tmp:
        _figures(data, pred, material, tmp)
        images = {name: (tmp / name).read_bytes() for name in FIGURES}
        (tmp / "report.json").write_text(json.dumps(rep, indent=2, allow_nan=False) + "\n", "utf-8")
        (tmp / "report.md").write_text(_markdown(rep), "utf-8")
        (tmp / "report.html").write_text(_html(rep, images), "utf-8")
    return rep
