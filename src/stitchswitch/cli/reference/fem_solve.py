"""``stitchswitch fem-solve``: one design with the shell reference; keypoints and the 3D surface."""
from __future__ import annotations

import json
import pathlib

import click

from stitchswitch.cli import options
from stitchswitch.cli.output import key_value_table
from stitchswitch.cli.reference.shell_options import shell_options
from stitchswitch.reduced.model.material_io import load_material
from stitchswitch.reduced.model.params import DEFAULT_MATERIAL, Patch


@click.command("fem-solve", cls=options.Command)
@click.option("--diameter", "-d", "diameter_mm", type=options.FINITE_FLOAT, required=True, metavar="MM")
@click.option("--fill", "-p", type=options.FINITE_FLOAT, required=True, metavar="P")
@options.material_opt
@click.option("--elements", type=click.IntRange(min=4, max=640), default=80, show_default=True,
              help="Hermite elements on the patch.")
@shell_options
@click.option("--mesh", type=click.Path(dir_okay=False, path_type=pathlib.Path), default=None,
              metavar="FILE", help="Write the surface of revolution (.vtu, .ply, .obj, ...).")
@options.json_opt
def fem_solve(diameter_mm, fill, material_path, elements, hoop_bending, poisson, start, mesh, as_json):
    """Solve one design with the scikit-fem shell reference (started from the reduced
    equilibrium, or by the prestretch continuation from the flat sheet) and print its
    keypoints; optionally export the 3D surface through meshio."""
    from stitchswitch.fem_reference.continuation import solve_reference
    from stitchswitch.fem_reference.shell import ShellModel
    from stitchswitch.files.revolution import surface_of_revolution, write_mesh
    from stitchswitch.reduced.model.keypoints import keypoints_from_profile

    patch = Patch(diameter_mm, fill)
    material = DEFAULT_MATERIAL if material_path is None else load_material(material_path)
    model = ShellModel(patch, material, elements_inside=elements, growth=1.0 + 3.2 / elements,
                       hoop_bending=hoop_bending, poisson=poisson)
    sol = solve_reference(model, start, max_iter=300)
    R, r, z, n_in = sol.sample()
    kp = keypoints_from_profile(R, r, z, n_in)
    if mesh is not None:
        points, tris = surface_of_revolution(r, z)
        write_mesh(mesh, points, tris, {"height_mm": points[:, 2]} if mesh.suffix == ".vtu" else None)
    out = {"d_mm": diameter_mm, "fill": fill, "h_mm": kp.h_mm, "r_a_mm": kp.r_a_mm,
           "z_a_mm": kp.z_a_mm, "r_b_mm": kp.r_b_mm, "z_b_mm": kp.z_b_mm, "energy": sol.energy,
           "residual": sol.residual, "converged": sol.converged, "iterations": sol.iterations,
           "solve_s": sol.solve_s, "start": start, "hoop_bending": hoop_bending, "poisson": poisson}
    if as_json:
        click.echo(json.dumps(out))
    else:
        click.echo(key_value_table(((k, f"{v:.4g}" if isinstance(v, float) else v)
                                    for k, v in out.items()), gap=1))
    if not sol.converged:
        click.echo("warning: the shell solve did not converge", err=True)
