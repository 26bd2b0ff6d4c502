"""``stitchswitch preview``: a 3D preview of a design (PNG, offscreen), or one patch's profile."""
from __future__ import annotations

import time

import click

from stitchswitch.cli import options
from stitchswitch.cli.output import key_value_table
from stitchswitch.errors import InvalidInputError
from stitchswitch.files.extensions import check_extension
from stitchswitch.files.outputs import check_distinct, together
from stitchswitch.preview3d.camera import VIEWS
from stitchswitch.preview3d.colours import COLOURS
from stitchswitch.preview3d.mesh_io import MESH_EXTENSIONS
from stitchswitch.preview3d.render import EXAGGERATE_RANGE
from stitchswitch.reduced.model.params import DIAMETER_RANGE_MM


@click.command(cls=options.Command)
@click.argument("design", required=False, type=click.Path(dir_okay=False))
@click.option("--output", "-o", type=options.OutputFile(
                  (".png", ".svg"), "the 3D preview of a design is written as .png, a single "
                  "patch's profile as .png or .svg", as_str=True),
              required=True, metavar="FILE",
              help="Image to write: .png (design), .png or .svg (single patch).")
@click.option("--state", type=click.Choice(["up", "down", "mixed"]), default=None,
              help="Pop every patch up or down, or mixed: each patch's own state "
                   "(default mixed for a design, up for a single patch).")
@click.option("--view", type=click.Choice([*VIEWS, "section"]), default=None,
              help="Camera: iso (default), top or side; or section: the cut through the "
                   "patch given by --patch (y = its centre).")
@click.option("--piece", default=None, metavar="NAME",
              help="Frame the camera on this piece (default: on the patches).")
@click.option("--patch", "patch_id", default=None, metavar="ID",
              help="Frame the camera on this patch; the patch of --view section.")
@click.option("--exaggerate", type=options.BoundedFloat(*EXAGGERATE_RANGE), default=None,
              metavar="K", help="Draw heights K times taller (stated on the image; colours and "
                                "--mesh keep the true heights)  [default: 1]")
@click.option("--size", default=None, metavar="WxH",
              help="Image size in pixels (default 1200x900).")
@click.option("--mesh", "mesh_path", type=options.OutputFile(MESH_EXTENSIONS, as_str=True),
              default=None, metavar="FILE",
              help="Also write the surface mesh (.vtu, .ply or .obj, garment mm), together with "
                   "-o: both or neither.")
@click.option("--color", "colour", type=click.Choice(list(COLOURS)), default=None,
              help="Colour by height (default) or by constraint violations.")
@click.option("--diameter", "-d", "diameter_mm", type=options.FINITE_FLOAT, default=None,
              metavar="MM", help="Single-patch view: diameter on the pre-stretched fabric.")
@click.option("--fill", "-p", type=options.FINITE_FLOAT, default=None, metavar="P",
              help="Single-patch view: fill fraction in (0, 1].")
@options.material_opt
def preview(design, output, state, view, piece, patch_id, exaggerate, size, mesh_path, colour,
            diameter_mm, fill, material_path):
    """Render DESIGN (a design JSON file) in 3D offscreen, or, with --diameter and --fill
    instead of DESIGN, draw one patch's profile with its keypoints and dimensions."""
    single = diameter_mm is not None or fill is not None
    if design is not None and single:
        raise InvalidInputError("give either a DESIGN file or --diameter/--fill, not both")
    if design is None and not single:
        raise InvalidInputError("give a DESIGN file, or --diameter and --fill for a single patch")
    check_distinct({"--output": output, "--mesh": mesh_path})
    frame = {"--piece": piece, "--patch": patch_id, "--exaggerate": exaggerate}
    if single:
        _single(output, diameter_mm, fill, state, view, size, colour, mesh_path, material_path,
                frame)
    else:
        _design(design, output, state or "mixed", view or "iso", size, colour or "height",
                mesh_path, material_path, piece, patch_id, exaggerate or 1.0)


def _check_frame(path, design, view, piece, patch_id, colour) -> None:
    """--piece / --patch name a piece / patch of the design; --view section needs --patch."""
    if piece is not None and patch_id is not None:
        raise InvalidInputError("give --piece or --patch, not both")
    if piece is not None and piece not in [p.name for p in design.pieces]:
        raise InvalidInputError(f"--piece: {path} has no piece {piece!r}; its pieces: "
                                + ", ".join(p.name for p in design.pieces))
    ids = [p.id for p in design.patches]
    if patch_id is not None and patch_id not in ids:
        raise InvalidInputError(f"--patch: {path} has no patch {patch_id!r}"
                                + (f"; its patches: {', '.join(ids[:12])}"
                                   + (", ..." if len(ids) > 12 else "") if ids else ""))
    if view == "section":
        if patch_id is None:
            raise InvalidInputError("--view section needs --patch ID (the patch to cut through)")
        if colour == "violations":
            raise InvalidInputError("--color violations applies to the 3D views, not to "
                                    "--view section")


def _design(path, output, state, view, size, colour, mesh_path, material_path, piece=None,
            patch_id=None, exaggerate=1.0):
    from stitchswitch.layout.garment.design_io import load_design
    from stitchswitch.preview3d import colours, mesh_io, render
    from stitchswitch.preview3d.scene import build_scene
    from stitchswitch.preview3d.spec import spec_from_design

    if material_path is not None:
        raise InvalidInputError("--material is for the single-patch view; a design file names "
                                "its own material")
    check_extension(output, (".png",), hint="the 3D preview is written as .png")
    section = view == "section"
    opts = render.RenderOptions(view="iso" if section else view,
                                size=render.parse_size(size or "1200x900"), colour=colour,
                                exaggerate=exaggerate, piece=piece, patch=patch_id)
    t0 = time.perf_counter()
    design = load_design(path)
    _check_frame(path, design, view, piece, patch_id, colour)
    status = violations = None
    lo, hi = DIAMETER_RANGE_MM
    outside = [p for p in design.patches if not lo <= p.diameter_mm <= hi]
    if colour == "violations":
        patch_status, piece_status, violations = colours.design_status(design)
        status = (patch_status, piece_status)
        design = design.with_patches(p for p in design.patches if p not in outside)
    elif outside:
        raise InvalidInputError(
            f"{path}: patch {outside[0].id} has d = {outside[0].diameter_mm:g} mm, outside the "
            f"model's range [{lo:g}, {hi:g}] mm, so its shape cannot be predicted "
            "(stitchswitch check lists every such patch; --color violations draws the rest)")
    scene = build_scene(spec_from_design(design).with_state(state))
    if section:
        from stitchswitch.preview3d.single import section_bytes
        png = section_bytes(scene, patch_id, opts.size, exaggerate)
    else:
        png = render.png_bytes(render.render_scene(scene, opts, status)[0])
    from stitchswitch.files.atomic import atomic_write_bytes
    with together({"--output": output, "--mesh": mesh_path}) as tmp:
        if mesh_path is not None:
            n_points = mesh_io.write_scene_mesh(tmp["--mesh"], scene)
        atomic_write_bytes(tmp["--output"], png)
    ups = sum(p.state == "up" for p in scene.patches)
    rows = [("design", path),
            ("pieces", str(len(scene.pieces))),
            ("patches", f"{len(scene.patches)} ({ups} up, {len(scene.patches) - ups} down)"),
            ("view", _view_text(view, opts, colour, piece, patch_id, exaggerate))]
    if violations is not None:
        n_err = sum(v.severity == "error" for v in violations)
        rows.append(("violations", f"{n_err} errors, {len(violations) - n_err} warnings"))
        rows += [(f"{v.severity} {v.rule}", f"{v.message}; fix: {v.hint}" if v.hint
                  else v.message) for v in violations]
        if outside:
            rows.append(("not drawn", ", ".join(p.id for p in outside)
                         + ": outside the model's range (model-range)"))
    rows.append(("image", output))
    if mesh_path is not None:
        rows.append(("mesh", f"{mesh_path} ({n_points} points)"))
    rows.append(("time", f"{time.perf_counter() - t0:.2f} s"))
    click.echo(key_value_table(rows))


def _view_text(view, opts, colour, piece, patch_id, exaggerate) -> str:
    size = f"{opts.size[0]}x{opts.size[1]} px"
    k = f"heights x {exaggerate:g}"
    if view == "section":
        return f"section through patch {patch_id}, {size}, {k}"
    where = (f"piece {piece}" if piece is not None else f"patch {patch_id}"
             if patch_id is not None else "the patches")
    return f"{view}, {size}, colour by {colour}, framed on {where}, {k}"


def _single(output, diameter_mm, fill, state, view, size, colour, mesh_path, material_path,
            frame):
    from stitchswitch.preview3d import mesh_io, single
    from stitchswitch.preview3d.profiles import single_profile
    from stitchswitch.preview3d.scene import build_scene
    from stitchswitch.preview3d.spec import PreviewPatch, PreviewSpec
    from stitchswitch.reduced.model.material_io import load_material
    from stitchswitch.reduced.model.params import DEFAULT_MATERIAL

    if diameter_mm is None or fill is None:
        raise InvalidInputError("the single-patch view needs both --diameter and --fill")
    for name, value in (("--view", view), ("--size", size), ("--color", colour), *frame.items()):
        if value is not None:
            raise InvalidInputError(f"{name} applies to the 3D preview of a design, "
                                    "not to the single-patch view")
    if state == "mixed":
        raise InvalidInputError("--state mixed needs a design; a single patch is up or down")
    state = state or "up"
    ext = single.check_figure_path(output)
    material = DEFAULT_MATERIAL if material_path is None else load_material(material_path)
    profile = single_profile(diameter_mm, fill, material)
    name = "default" if material_path is None else str(material_path)
    data = single.figure_bytes(profile, ext, state, name, material.eta)
    if mesh_path is not None:
        spec = PreviewSpec((), (PreviewPatch("patch", (0.0, 0.0), diameter_mm, fill, state),),
                           material)
        scene = build_scene(spec)
    from stitchswitch.files.atomic import atomic_write_bytes
    with together({"--output": output, "--mesh": mesh_path}) as tmp:
        if mesh_path is not None:
            n_points = mesh_io.write_scene_mesh(tmp["--mesh"], scene)
        atomic_write_bytes(tmp["--output"], data)
    kp = profile.keypoints
    rows = [("design", f"d = {diameter_mm:g} mm, fill = {fill:g}, popped {state}"),
            ("profile", "design map" if profile.source == "map" else "direct solve"),
            ("h", f"{kp.h_mm:.3f} mm"),
            ("a", f"r_a = {kp.r_a_mm:.3f} mm, z_a = {kp.z_a_mm:.3f} mm"),
            ("b", f"r_b = {kp.r_b_mm:.3f} mm, z_b = {kp.z_b_mm:.3f} mm ({kp.b_rule})"),
            ("figure", output)]
    if mesh_path is not None:
        rows.append(("mesh", f"{mesh_path} ({n_points} points)"))
    click.echo(key_value_table(rows))
