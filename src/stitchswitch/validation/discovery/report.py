"""The discovery report: a short story in Markdown and HTML with PNG figures, and report.json.

The directory follows ``validation.report``'s conventions (``stitchswitch.files.outdir``): it is built
in a temporary directory next to the target and renamed into place as a whole (nothing is left
behind on error); an existing target must be empty or a previous report of this command (its
report.json says ``"generator": "stitchswitch discover"`` and it holds no other files), which is
replaced. The HTML is self-contained (``files.html_page``, figures as data URIs). report.json
holds no timestamps or timings: equal inputs give equal files.
"""
from __future__ import annotations

import json
import os

from stitchswitch import __version__
from stitchswitch.files.html_page import Figure, ItemList, Markup, Paragraph, Section, Table, code, inline, page, strong
from stitchswitch.files.jsonsafe import json_safe
from stitchswitch.files.outdir import check_outdir, previous_output, write_outdir
from stitchswitch.reduced.model.material_io import material_hash
from stitchswitch.validation.discovery.effects import get_effect
from stitchswitch.validation.discovery.figures import FIGURES, all_figures
from stitchswitch.validation.discovery.proposal import template_csv
from stitchswitch.validation.measured import QUANTITIES
from stitchswitch.validation.report import provenance_statement

__all__ = ["GENERATOR", "REPORT_FILES", "METHOD", "report_dict", "check_discovery_dir",
           "estimate_how",
           "write_discovery_report", "report_json"]

GENERATOR = "stitchswitch discover"
REPORT_FILES = ("report.md", "report.html", "report.json", "next_samples.csv") + FIGURES
METHOD = {
    "calibration": "least squares (scipy trust-region 'trf', forward finite-difference "
                   "Jacobian) of the MSE over h, r_a, z_a, r_b, z_b of the training rows; "
                   "k_theta_fab (overall scale) and w_log held fixed",
    "residual_test": "per quantity, on all rows: leave-one-out cross-validated R^2 of a "
                     "quadratic surface in (d, p) against predicting zero, p-value by "
                     "randomization (permutations with sign flips); systematic if p < "
                     "alpha / 5",
    "ranking": "K-fold cross-validated MSE on the training rows after refitting all "
               "coefficients and the effect's parameters (cross-validation is the complexity "
               "penalty); the validation rows take no part",
    "significance": "the best-ranked candidate is named only if it beats the starting model's "
                    "cross-validated MSE and an F test of its training-RSS drop against the "
                    "noise variance (estimated from its residuals) gives p < alpha / number of "
                    "candidates",
    "signature": "finite-difference change of the keypoints per unit strength at the "
                 "calibrated starting model (zero to the probe value); correlated with the "
                 "residuals after removing what recalibrating the coefficients can absorb",
}


def report_dict(disc, data, start, start_label: str = "default") -> dict:
    """report.json: the discovery summary plus provenance and every row."""
    rows = []
    for i, r in enumerate(data.rows):
        rows.append({"line": r.line, "sample_id": r.sample_id, "split": r.split,
                     "d_mm": r.diameter_mm, "fill": r.fill,
                     "measured": {q: float(disc.measured[i, k]) for k, q in enumerate(QUANTITIES)},
                     "before": {q: float(disc.before[i, k]) for k, q in enumerate(QUANTITIES)},
                     "after": {q: float(disc.after[i, k]) for k, q in enumerate(QUANTITIES)}})
    s = disc.summary
    return json_safe({
        "generator": GENERATOR, "version": __version__,
        "missing_effect": s["missing_effect"], "significant": s["significant"],
        "effect_parameters": s["effect_parameters"], "estimate": s.get("estimate"),
        "decision": s["decision"],
        "ranking": s["ranking"], "before": s["before"], "after": s["after"],
        "verdict": s["verdict"], "indistinguishable": s["indistinguishable"],
        "missing_effects": s["missing_effects"], "forward": s["forward"],
        "after_model": s["after_model"], "claims": s["claims"],
        "unexplained_residual": s["unexplained_residual"], "noise_floor": s["noise_floor"],
        "systematic": s["systematic"], "proposal": s["proposal"], "robust": s["robust"],
        "relative_noise": s.get("relative_noise"),
        "data": {"path": data.path, "source": data.source, "synthetic": data.synthetic,
                 "provenance": provenance_statement(data), "sha256": data.sha256,
                 "n_train": s["n_train"], "n_val": s["n_val"]},
        "start_material": {"label": start_label, "sha256": material_hash(start),
                           "values": start.as_dict()},
        "starting_model": s["starting_model"],
        "residuals_before": s["residuals_before"], "residuals_after": s["residuals_after"],
        "significance_threshold": s["significance_threshold"],
        "method": METHOD, "config": s["config"],
        "rows": rows, "files": list(REPORT_FILES),
    })


def report_json(rep: dict) -> str:
    return json.dumps(rep, indent=2, allow_nan=False) + "\n"


def check_discovery_dir(outdir) -> bool:
    """Raise ``InvalidInputError`` unless ``outdir`` can take a report; True if it holds a
    previous discovery report that will be replaced."""
    return check_outdir(outdir, previous=_PREVIOUS, what="report directory")


_PREVIOUS = previous_output(REPORT_FILES, GENERATOR, noun="discovery report")


# ----------------------------------------------------------------------------- the story

def _f(v, n=2):
    return "n/a" if v is None else f"{v:.{n}f}"


def _story(rep: dict) -> dict:
    """The report's sections as (title, paragraphs, table, figures) pieces shared by MD/HTML."""
    s0 = rep["starting_model"]
    res_b = rep["residuals_before"]
    systematic = [q for q in QUANTITIES if res_b[q]["systematic"]]
    where = (f"The residuals of {', '.join(systematic)} are systematic over the design space "
             "(a smooth function of d and p predicts them on rows it has not seen)."
             if systematic else "No quantity's residuals are distinguishable from noise by the "
                                "residual test.")
    calib = (f"The starting model ({s0['label']}) was calibrated on the {rep['data']['n_train']} "
             f"training rows: training MSE {s0['train_mse_mm2']:.3f} mm^2, cross-validated MSE "
             f"{s0['cv_score_mm2']:.3f} mm^2. Fitted: " +
             ", ".join(f"{k} = {v:.4g}" for k, v in s0["parameters"].items()) + ".")
    res_table = [["quantity", "RMS (mm)", "mean (mm)", "CV R^2", "p", "verdict"]] + [
        [q, _f(res_b[q]["rms_mm"]), _f(res_b[q]["mean_mm"]), _f(res_b[q]["cv_r2"]),
         f"{res_b[q]['p_value']:.3g}", "systematic" if res_b[q]["systematic"] else "noise-like"]
        for q in QUANTITIES]
    rank_table = [["rank", "effect", "CV MSE (mm^2)", "F", "p", "significant", "fitted strength",
                   "signature corr.", "unabsorbed", "val MAE h before/after",
                   "val MAE r_a before/after", "CV folds stuck"]]
    for r in rep["ranking"]:
        sig = r["signature"]
        rank_table.append([
            str(r["rank"]), r["effect"], _f(r["score"], 3), _f(r["f_statistic"], 1),
            f"{r['p_value']:.2g}", "yes" if r["significant"] else "no",
            ", ".join(f"{k} = {v:.4g}" for k, v in r["effect_parameters"].items()),
            f"{sig['correlation']:+.2f}", f"{sig['unabsorbed']:.2f}",
            f"{r['val_mae_before']['h']:.2f} / {r['val_mae_after']['h']:.2f}",
            f"{r['val_mae_before']['r_a']:.2f} / {r['val_mae_after']['r_a']:.2f}",
            f"{r.get('cv_stuck_folds', 0)} / {r.get('cv_folds', 0)}"])
    stuck = [(r["effect"], r.get("cv_stuck_folds", 0), r.get("cv_folds", 0))
             for r in [{"effect": "the starting model", **s0}] + rep["ranking"]
             if r.get("cv_stuck_folds", 0)]
    stuck_text = ("" if not stuck else
                  "Stuck folds: in " + "; ".join(f"{k} of {n} folds for {name}"
                                                 for name, k, n in stuck) +
                  ", the fold's refit kept the full fit's parameters (each step was rejected "
                  "within its budget). Those folds' rows are predicted by a fit that saw them, "
                  "so these cross-validated errors are partly training errors.")
    name = rep["missing_effect"]
    if name:
        top = rep["ranking"][0]
        sig = top["signature"]
        best_q = max(QUANTITIES, key=lambda q: abs(sig["per_quantity"][q]))
        verdict = (f"Missing effect: **{name}** ({get_effect(name).summary}). " + rep["decision"] +
                   ". Fitted: " + ", ".join(f"{k} = {v:.4g}" for k, v in
                                             rep["effect_parameters"].items()) + _estimate(rep) + ".")
        evidence = (f"Why it matches: {unabs(sig['unabsorbed'])} of its signature cannot be "
                    f"absorbed by recalibrating the coefficients, and that part correlates with "
                    f"the residual pattern at {sig['correlation']:+.2f} over all quantities "
                    f"(strongest in {best_q}: {sig['per_quantity'][best_q]:+.2f}).")
    elif rep.get("indistinguishable"):
        verdict = ("**The data cannot tell apart " + " / ".join(rep["indistinguishable"]) +
                   "**: " + rep["decision"] + ". What would separate them: " + "; ".join(
                       f"{' vs '.join(s['models'])} at d = {s['d_mm']:g} mm, p = {s['fill']:g} "
                       f"({s['sigmas']:.1f} sigma)" for s in rep["proposal"]["separation"]) + ".")
        evidence = ("The \"after\" predictions use the best-ranked of the group, "
                    f"{rep['after_model']}, for display only.")
    else:
        verdict = "No missing effect was found: " + rep["decision"] + "."
        evidence = ("The ranking and the signatures below are reported for inspection; none of "
                    "them is a significant improvement over the starting model.")
    gap_table = [["quantity", "MAE before (mm)", "MAE after (mm)", "error % before",
                  "error % after"]] + [
        [q, _f(rep["before"][q]["mae_mm"]), _f(rep["after"][q]["mae_mm"]),
         _f(rep["before"][q]["pct_error"], 1), _f(rep["after"][q]["pct_error"], 1)]
        for q in QUANTITIES]
    left = rep["unexplained_residual"]
    noise = rep["noise_floor"]["sigma_mm"]
    share = rep["systematic"]["share_explained"]
    after_text = (("**An unexplained residual remains** in " + ", ".join(left) +
                   " (map below).") if left else
                  "After the change no quantity's residuals test as systematic.")
    after_text += (" Estimated noise floor (" + rep["noise_floor"]["how"] + "): sigma " +
                   ", ".join(f"{q} {noise[q]:.2f}" for q in QUANTITIES) + " mm. Share of the "
                   "systematic residual explained: " +
                   ("n/a" if share is None else f"{100 * share:.0f} %") + ".")
    rel = rep.get("relative_noise")
    if rel:
        after_text += (" Noise proportional to the keypoint size: the fits, errors (mm^2), tests "
                       "and the noise floor are on the keypoints divided by their size relative "
                       "to the mean (mean sizes " + ", ".join(
                           f"{q} {rel['mean_size_mm'][q]:.2f}" for q in QUANTITIES) +
                       " mm); the validation MAE and the figures are in mm.")
    down = rep["robust"]["down_weighted"]
    if down:
        after_text += (f" Robust fit (Huber, c = {rep['robust']['huber_c']:g} robust sigmas); "
                       "down-weighted: " + ", ".join(f"{d['sample']} {d['quantity']} (weight "
                                                     f"{d['weight']:.2f})" for d in down) + ".")
    if rep["proposal"]["designs"]:
        after_text += (" Next samples (next_samples.csv, in the order chosen, with the expected chi^2 each adds): " +
                       "; ".join(f"d = {r['d_mm']:g} mm, p = {r['fill']:g} (chi^2 "
                                 f"{r['gain']:.1f})" for r in rep["proposal"]["designs"])
                       + ".")
    return {"calib": calib, "where": where, "res_table": res_table, "rank_table": rank_table,
            "stuck_text": stuck_text,
            "verdict": verdict, "evidence": evidence, "gap_table": gap_table,
            "after_text": after_text}


def estimate_how(estimate: dict) -> str:
    """How the named model's estimate was refitted (``estimate``: the summary's record)."""
    prior = estimate.get("prior_start", {}).get("kept") == "prior"
    return ("its strength profiled" + (", then from the starting material's own coefficients"
                                       if prior else ""))


def _estimate(rep: dict) -> str:
    """How the reported strength was estimated after the decision (empty if not recorded)."""
    e = rep.get("estimate")
    if not e:
        return ""
    return (f" (the named model refitted after the decision, {estimate_how(e)}: "
            f"training MSE {e['train_mse_mm2_before']:.3f} -> {e['train_mse_mm2']:.3f} mm^2; the "
            "ranking shows the fit that was tested)")


def unabs(x: float) -> str:
    return f"{100 * x:.0f} %"


def _md_table(rows) -> list[str]:
    md = lambda cells: "| " + " | ".join(str(c).replace("|", "\\|") for c in cells) + " |"  # noqa: E731
    return [md(rows[0]), md(["---"] * len(rows[0]))] + [md(r) for r in rows[1:]]


def _markdown(rep: dict) -> str:
    st = _story(rep)
    d = rep["data"]
    lines = ["# Discrepancy discovery", "", f"> **{d['provenance']}**", "",
             f"- data: `{d['path']}` (sha256 `{d['sha256']}`), {d['n_train']} train / "
             f"{d['n_val']} val rows", f"- source line: {d['source']}",
             f"- starting material: {rep['start_material']['label']} (sha256 "
             f"`{rep['start_material']['sha256']}`)", "",
             "## 1. Where the model is wrong", "", st["calib"], "", st["where"], ""]
    lines += _md_table(st["res_table"])
    lines += ["", "![residuals before](residuals_before.png)", "",
              "## 2. Candidate effects, refitted and ranked", "",
              f"Ranking: {METHOD['ranking']}. Significance: {METHOD['significance']} "
              f"(threshold {rep['significance_threshold']:.3g}).", ""]
    lines += _md_table(st["rank_table"])
    lines += ["", st["stuck_text"]] if st["stuck_text"] else []
    lines += ["", "![ranking](ranking.png)", "", "## 3. The evidence", "", st["verdict"], "",
              st["evidence"], "", "![signatures](signatures.png)", "",
              "## 4. The gap before and after, validation rows", ""]
    lines += _md_table(st["gap_table"])
    lines += ["", "![before and after](before_after.png)", "", st["after_text"], "",
              "![residuals after](residuals_after.png)", "", "## Method", ""]
    lines += [f"- {k}: {v}" for k, v in METHOD.items()]
    lines += ["", f"Generated by {rep['generator']} {rep['version']}; the numbers are in "
              "report.json.", ""]
    return "\n".join(lines)


def _table(rows) -> Table:
    return Table(tuple(rows[1:]), head=tuple(rows[0]), cls="numbers", scroll=True)


def _bold(text: str) -> Markup:
    """Markdown ``**bold**`` as HTML, the rest escaped."""
    return inline(*(strong(p) if i % 2 else p for i, p in enumerate(text.split("**"))))


def _html(rep: dict, images: dict) -> str:
    st = _story(rep)
    d = rep["data"]
    kind = "synthetic" if d["synthetic"] else ("unspecified" if d["source"] == "unspecified" else "measured")

    def img(name, alt):
        return Figure(images[name], alt, cls="wide")

    blocks = (
        Paragraph(d["provenance"], cls=f"banner {kind}"),
        Paragraph(inline("data ", code(d["path"]), " (sha256 ", code(d["sha256"]),
                         f"), {d['n_train']} train / {d['n_val']} val rows; starting material "
                         f"{rep['start_material']['label']}"), cls="note"),
        Section("1. Where the model is wrong", (
            Paragraph(st["calib"]), Paragraph(st["where"]), _table(st["res_table"]),
            img("residuals_before.png", "residual maps before"))),
        Section("2. Candidate effects, refitted and ranked", (
            Paragraph(f"Ranking: {METHOD['ranking']}. Significance: {METHOD['significance']} "
                      f"(threshold {rep['significance_threshold']:.3g}).", cls="note"),
            _table(st["rank_table"]),
            *([Paragraph(st["stuck_text"], cls="note")] if st["stuck_text"] else []),
            img("ranking.png", "ranking"))),
        Section("3. The evidence", (
            Paragraph(_bold(st["verdict"])), Paragraph(st["evidence"]),
            img("signatures.png", "signatures"))),
        Section("4. The gap before and after, validation rows", (
            _table(st["gap_table"]), img("before_after.png", "before and after"),
            Paragraph(_bold(st["after_text"])), img("residuals_after.png", "residual maps after"))),
        Section("Method", (
            ItemList(tuple(inline(strong(k), f": {v}") for k, v in METHOD.items()), cls="note"),)),
    )
    return page(f"stitchswitch discovery: {os.path.basename(d['path'])}", blocks,
                heading="Discrepancy discovery",
                footer=f"Generated by {rep['generator']} {rep['version']}. The numbers are in "
                       "report.json; the figures are also saved as PNG files next to this page.")


def write_discovery_report(disc, data, start, outdir, start_label: str = "default") -> dict:
    """Write the report directory ``outdir`` as a whole; returns the content of report.json."""
    check_discovery_dir(outdir)
    rep = report_dict(disc, data, start, start_label)
    images = all_figures(disc)
    files = dict(images)
    files["report.json"] = report_json(rep).encode("utf-8")
    files["next_samples.csv"] = template_csv(rep["proposal"]).encode("utf-8")
    files["report.md"] = lambda: _markdown(rep).encode("utf-8")
    files["report.html"] = lambda: _html(rep, images).encode("utf-8")
    write_outdir(outdir, files, previous=_PREVIOUS)
    return rep
