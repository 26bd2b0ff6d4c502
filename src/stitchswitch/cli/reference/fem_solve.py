"""``stitchswitch fem-solve``: one design with the shell of revolution; keypoints and the 3D surface."""
from __future__ import annotations

import json
import logging

import click

from stitchswitch.cli import options
from stitchswitch.cli.output import key_value_table
from stitchswitch.cli.reference.shell_options import shell_options, shell_params
from stitchswitch.files.outputs import together
from stitchswitch.files.revolution import MESH_EXTENSIONS
from stitchswitch.reduced.model.material_io import load_material
from stitchswitch.reduced.model.params import DEFAULT_MATERIAL, Patch


@click.command("fem-solve", cls=options.Command)
@click.option("--diameter", "-d", "diameter_mm", type=options.FINITE_FLOAT, required=True, metavar="MM",
              help="Patch diameter on the pre-stretched fabric (mm).")
@click.option("--fill", "-p", type=options.FINITE_FLOAT, required=True, metavar="P",
              help="Embroidery fill fraction, in (0, 1].")
@options.material_opt
@shell_options
@click.option("--mesh", type=options.OutputFile(MESH_EXTENSIONS), default=None,
              metavar="FILE", help="Write the surface of revolution (.vtu, .ply, .obj, ...).")
@options.json_opt
def fem_solve(diameter_mm, fill, material_path, nu, kappa0_per_mm, thickness_mm, elements, mesh, as_json):
    """Solve one design with the Kirchhoff-Love shell of revolution (Newton from the reduced
    model's equilibrium as the starting guess) and print its keypoints and certificate;
    optionally export the 3D surface through meshio."""
    from stitchswitch.fem_reference.revolution.solve import equilibrium
    from stitchswitch.files.revolution import surface_of_revolution, write_mesh

    patch = Patch(diameter_mm, fill)
    params = shell_params(nu, kappa0_per_mm, thickness_mm, elements)
    material = DEFAULT_MATERIAL if material_path is None else load_material(material_path)
    st = equilibrium(patch, material, params)
    kp = st.keypoints
    if mesh is not None:
        _, r, z, _ = st.profile()
        points, tris = surface_of_revolution(r, z - z[-1])
        with together({"--mesh": mesh}) as tmp:
            write_mesh(tmp["--mesh"], points, tris,
                       {"height_mm": points[:, 2]} if mesh.suffix == ".vtu" else None)
    out = {"d_mm": diameter_mm, "fill": fill, "h_mm": kp.h_mm, "r_a_mm": kp.r_a_mm,
           "z_a_mm": kp.z_a_mm, "r_b_mm": kp.r_b_mm, "z_b_mm": kp.z_b_mm, "energy": st.energy,
           "residual": st.residual, "converged": st.converged, "certified": st.certified,
           "lowest_eigenvalue": st.lowest_eigenvalue, "iterations": st.iterations,
           "solve_s": st.solve_s, "nu": nu, "kappa0_per_mm": kappa0_per_mm}
    if as_json:
        click.echo(json.dumps(out))
    else:
        click.echo(key_value_table(((k, f"{v:.4g}" if isinstance(v, float) else v)
                                    for k, v in out.items()), gap=1))
    if not st.certified:
        logging.getLogger(__name__).warning(
            "the shell solve is not certified (not converged or not a strict minimum)")
