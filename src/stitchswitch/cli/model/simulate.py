"""``stitchswitch simulate``: solve one patch design and print its keypoints."""
from __future__ import annotations

import json
import logging

import click

from stitchswitch.cli import options
from stitchswitch.cli.output import key_value_table
from stitchswitch.files.atomic import atomic_write_text
from stitchswitch.files.jsonsafe import json_safe
from stitchswitch.files.outputs import together
from stitchswitch.reduced.model.material_io import load_material, material_hash
from stitchswitch.reduced.model.params import DEFAULT_MATERIAL, Patch
from stitchswitch.reduced.solvers.solve import Solution, solve

log = logging.getLogger(__name__)


@click.command(cls=options.Command)
@options.diameter_opt
@options.fill_opt
@options.material_opt
@options.solver_opt
@options.max_iter_opt
@options.json_opt
@click.option("--profile-csv", type=options.OutputFile((".csv",), "the profile is written as CSV", as_str=True),
              default=None, metavar="FILE",
              help="Also write the profile (columns R_mm,r_mm,z_mm) to FILE.")
def simulate(diameter_mm, fill, material_path, solver, max_iter, as_json, profile_csv):
    """Equilibrium profile of one circular patch (default: d = 40 mm, fill = 0.8).

    Prints h, r_a, z_a, r_b, z_b (mm) and the solver certificate. A solve that does not
    converge is still reported, with a warning on stderr, and exits 0; the JSON output
    carries "converged": false.
    """
    patch = Patch(diameter_mm, fill)
    material = DEFAULT_MATERIAL if material_path is None else load_material(material_path)
    log.info("solving d = %g mm, fill = %g with %s, material %s (sha256 %s)",
             patch.diameter_mm, patch.fill, solver, material_path or "default",
             material_hash(material)[:12])
    sol = solve(patch, material, solver=solver, max_iter=max_iter)
    if not sol.converged:
        log.warning("the %s solve did not converge (residual %.2e > tol %.0e after %d "
                    "iterations); the result is not a certified equilibrium",
                    solver, sol.residual, sol.tol, sol.iterations)
    if profile_csv is not None:
        with together({"--profile-csv": profile_csv}) as tmp:
            atomic_write_text(tmp["--profile-csv"], profile_csv_text(sol))
    click.echo(json.dumps(json_safe(sol.as_dict())) if as_json else table(sol, material_path))


def table(sol: Solution, material_path=None) -> str:
    """The human-readable summary: one aligned ``name  value`` row per quantity."""
    kp = sol.keypoints
    mm = lambda v: f"{v:.3f} mm"  # noqa: E731
    rows = [
        ("design", f"d = {sol.patch.diameter_mm:g} mm, fill = {sol.patch.fill:g}"),
        ("material", str(material_path) if material_path else "default"),
        ("solver", sol.solver),
        ("h", mm(kp.h_mm)),
        ("r_a", mm(kp.r_a_mm)),
        ("z_a", mm(kp.z_a_mm)),
        ("r_b", f"{mm(kp.r_b_mm)}  ({kp.b_rule})" if kp.b_rule else mm(kp.r_b_mm)),
        ("z_b", mm(kp.z_b_mm)),
        ("energy", f"{sol.energy:.6g}"),
        ("residual", f"{sol.residual:.2e}  (tol {sol.tol:.0e})"),
        ("converged", "yes" if sol.converged else "NO"),
        ("iterations", str(sol.iterations)),
        ("solve time", f"{sol.solve_s * 1e3:.0f} ms"),
    ]
    return key_value_table(rows)


def profile_csv_text(sol: Solution) -> str:
    """The profile as CSV: a ``#`` comment line, a header, one row per node (exact floats)."""
    lines = [f"# stitchswitch profile, d_mm={sol.patch.diameter_mm!r}, fill={sol.patch.fill!r}, "
             f"solver={sol.solver}",
             "R_mm,r_mm,z_mm"]
    lines += [f"{R!r},{r!r},{z!r}"
              for R, r, z in zip(sol.R_mm.tolist(), sol.r_mm.tolist(), sol.z_mm.tolist())]
    return "\n".join(lines) + "\n"
