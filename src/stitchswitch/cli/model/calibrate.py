"""``stitchswitch calibrate``: fit the material to measured keypoints by differential evolution."""
from __future__ import annotations

import json
import math
import pathlib
import sys
import time

import click

from stitchswitch.cli import options, progress
from stitchswitch.executor import default_workers, make_executor
from stitchswitch.files.atomic import atomic_write_text
from stitchswitch.files.outputs import check_distinct, together
from stitchswitch.reduced.calibration import evolution as cal
from stitchswitch.reduced.calibration.checkpoint import checkpoint_path, provenance_path, resume_point
from stitchswitch.reduced.model.material_io import canonical_json, load_material, material_hash
from stitchswitch.reduced.model.params import DEFAULT_MATERIAL

FREE = cal.DEFAULT_FREE


def _record(material, mse, data, settings, start_label, **state) -> dict:
    """Everything needed to trust and reproduce the fit, next to the material itself."""
    return {
        "material": material.as_dict(), "material_hash": material_hash(material),
        "train_mse_mm2": mse, "free_parameters": list(FREE),
        "fixed_parameters": {n: getattr(material, n) for n in cal.PARAMS if n not in FREE},
        "bounds": {k: list(v) for k, v in cal.BOUNDS.items()},
        "data": {"path": data.path, "sha256": data.sha256, "source": data.source,
                 "n_train": len(data.split("train"))},
        "start_material": start_label, "settings": settings, **state,
    }


def _record_text(record: dict) -> str:
    return json.dumps(record, indent=1, default=float) + "\n"


def _write_final(out: pathlib.Path, record: dict) -> None:
    """The material file (loadable with --material) and its provenance, as one unit."""
    from stitchswitch.reduced.model.params import Material

    with together({"--output": out, "provenance": provenance_path(out)}) as tmp:
        atomic_write_text(tmp["--output"], canonical_json(Material(**record["material"])))
        atomic_write_text(tmp["provenance"], _record_text(record))


@click.command(cls=options.Command)
@click.argument("data_path", metavar="DATA.csv", type=click.Path(dir_okay=False, path_type=pathlib.Path))
@options.material_opt
@click.option("--maxiter", type=click.IntRange(min=1), default=30, show_default=True, metavar="N",
              help="Differential-evolution generations.")
@click.option("--popsize", type=click.IntRange(min=2), default=10, show_default=True, metavar="N",
              help="Population size multiplier (scipy's popsize).")
@click.option("--seed", type=int, default=0, show_default=True, metavar="N",
              help="Seed of the differential evolution: the same seed gives the same material.")
@click.option("--workers", type=click.IntRange(min=1), default=None, metavar="N",
              help="Worker processes (default: one per core).")
@click.option("--scheduler", default=None, metavar="tcp://HOST:PORT",
              help="Evaluate on a Dask distributed cluster instead of local processes.")
@click.option("--resume", is_flag=True,
              help="Start from the best point of a previous, interrupted run with the same -o/--output.")
@options.deprecated_alias("--out", "-o/--output")("out_old", type=options.OutputFile((".json",)))
@click.option("--output", "-o", "out", type=options.OutputFile((".json",)), default=None,
              metavar="FILE.json", help="Required. Calibrated material (JSON), written when the search ends; "
                                   "provenance goes to FILE's stem + .calibration.json, the best "
                                   "point so far to FILE's stem + .checkpoint.json after every "
                                   "generation.")
@options.json_opt
def calibrate(data_path, material_path, maxiter, popsize, seed, workers, scheduler, resume,
              out_old, out, as_json):
    """Fit the material to the training rows of DATA.csv.

    Fitted: the seven coefficients but the overall scale k_theta_fab, the compressive ratios
    of the stitched mats and of the bare knit (c_emb, c_fab), the jamming stretch jam, the
    jammed knit's stiffness ratio c_jam and the hardening limit gamma_mm, by differential
    evolution and a final least-squares polish.
    The objective is the mean squared error over the five keypoints (the paper's). The best
    point so far is written to the checkpoint after every generation; -o/--output (and its
    provenance) only when the search ends, so an interrupted or killed run leaves an existing
    output file as it was, and can be continued with --resume.
    """
    from stitchswitch.validation.measured import load_measurements

    out = options.one_of(out, out_old, "-o/--output", "--out")
    checkpoint = checkpoint_path(out)
    check_distinct({"--output": out, "provenance": provenance_path(out), "checkpoint": checkpoint,
                    "DATA.csv": data_path})
    data = load_measurements(data_path)
    start = DEFAULT_MATERIAL if material_path is None else load_material(material_path)
    start_label = str(material_path) if material_path else "default"
    train = data.split("train")
    designs = [(r.diameter_mm, r.fill) for r in train]
    measured = data.keypoints("train")
    if resume:
        # DE starts again, with the previous best point as a member of its first population
        # (scipy does not expose the population to save it)
        start, previous = resume_point(out, data.sha256)
        start_label = f"resumed from {previous}"
    workers = workers or default_workers()
    settings = {"maxiter": maxiter, "popsize": popsize, "seed": seed, "workers": workers,
                "scheduler": scheduler, "resumed": resume,
                "objective": "MSE over h, r_a, z_a, r_b, z_b of the train rows (mm^2)"}
    t0 = time.perf_counter()

    def on_generation(gen, material, mse):
        atomic_write_text(checkpoint, _record_text(_record(
            material, mse, data, settings, start_label, generations=gen,
            elapsed_s=round(time.perf_counter() - t0, 2), message="in progress",
            interrupted=False)))
        progress.status(f"generation {gen}/{maxiter}: train MSE {mse:.4f} mm^2 "
                        f"({time.perf_counter() - t0:.0f} s)")

    with make_executor(workers, scheduler) as ex:
        result = cal.calibrate(designs, measured, start, maxiter=maxiter, popsize=popsize,
                               seed=seed, executor=ex if workers > 1 or scheduler else None,
                               callback=on_generation)
    record = _record(result.material, result.mse_mm2, data, settings, start_label,
                     generations=result.generations, evaluations=result.evaluations,
                     elapsed_s=round(result.elapsed_s, 2), message=result.message,
                     interrupted=result.interrupted, identifiability=result.identifiability)
    if result.interrupted:
        atomic_write_text(checkpoint, _record_text(record))
        click.echo(f"interrupted after {result.generations} generation(s): {out} left as it "
                   f"was; the best point so far is in {checkpoint} (continue with --resume)",
                   err=True)
        sys.exit(130)
    _write_final(out, record)
    checkpoint.unlink(missing_ok=True)
    if as_json:
        click.echo(json.dumps(record, default=float))
        return
    rmse = math.sqrt(result.mse_mm2) if math.isfinite(result.mse_mm2) else float("nan")
    click.echo(f"wrote {out} ({result.message}); train RMSE {rmse:.3f} mm over {len(train)} rows, "
               f"{result.generations} generations in {result.elapsed_s:.0f} s")
    for name in cal.PARAMS:
        tag = (" (fixed: overall scale)" if name == cal.SCALE_PARAM
               else " (fixed)" if name not in FREE else "")
        click.echo(f"  {name:12s} {getattr(result.material, name):10.4g}{tag}")
    weak = result.identifiability.get("weak_directions", [])
    if weak:
        click.echo("poorly identified combinations (small singular values of the keypoint Jacobian):")
        for w in weak:
            click.echo(f"  {w['direction']}  (singular value {w['singular_value']:.2e})")
