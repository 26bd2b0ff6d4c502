"""``stitchswitch patch``: tessellate a patch, plan its stitches, write an embroidery file."""
from __future__ import annotations

import click

from stitchswitch.cli import options
from stitchswitch.cli.output import key_value_table
from stitchswitch.errors import InvalidInputError
from stitchswitch.files.outputs import check_distinct, together
from stitchswitch.layout.check.constraints import CheckLimits
from stitchswitch.layout.check.rules.features import feature_sizes
from stitchswitch.layout.embroidery import export
from stitchswitch.layout.embroidery import stitch_preview as preview
from stitchswitch.layout.embroidery.machines import default_machine
from stitchswitch.layout.embroidery.patch_design import geometry_for
from stitchswitch.layout.embroidery.patch_geometry import make_patch, parse_selection
from stitchswitch.layout.embroidery.sewing.audit import audit
from stitchswitch.layout.embroidery.stitches import (
    ROW_SPACING_RANGE_MM,
    TRAVELS,
    StitchParams,
    plan_stitches,
)
from stitchswitch.layout.garment.design import CompositeSpec, PatchSpec

#: Tatami row spacings a machine can sew (finer rows would pile needle holes, coarser ones leave gaps).
ROW_SPACING = options.BoundedFloat(ROW_SPACING_RANGE_MM[0], ROW_SPACING_RANGE_MM[1])


@click.command(cls=options.Command)
@click.option("--diameter", "-d", "diameter_mm", type=options.FINITE_FLOAT, required=True,
              metavar="MM", help="Patch diameter in mm on the pre-stretched (hooped) fabric.")
@click.option("--fill", "-p", type=options.FINITE_FLOAT, required=True, metavar="P",
              help="Fill fraction in (0, 1]: stitched area / patch area.")
@click.option("--resolution", "resolution_mm", type=options.FINITE_FLOAT, default=5.0,
              show_default=True, metavar="MM", help="Triangle side of the tessellation.")
@click.option("--conductive", default=None, metavar="SPEC",
              help="Triangles in a second (conductive) thread: index:I,J | ring:K,.. | "
                   "annulus:INNER:OUTER | polygon:X,Y;X,Y;...")
@click.option("--core", "core", default=None, metavar="D,P",
              help="Composite patch: a concentric core of diameter D mm stitched at fill P "
                   "(e.g. a high-fill core in a low-fill surround).")
@click.option("--outline", default=None, metavar="X,Y;X,Y;...",
              help="Non-circular outer outline (mm, relative to the centre, inside the circle "
                   "of --diameter); needs --core.")
@click.option("--format", "fmt", default=None, metavar="FMT",
              help="Embroidery format (default: from the -o extension): "
                   + ", ".join(export.supported_formats()) + " ("
                   + ", ".join(f.upper() for f in export.EXPERIMENTAL)
                   + " experimental: their trims are not checked by an independent decoder).")
@click.option("--hoop", default=None, metavar="NAME",
              help="Hoop (SQ14b, RE20b, SQ20b, RE36b); default the smallest that fits.")
@click.option("--row-spacing", "row_spacing_mm", type=ROW_SPACING, default=0.4,
              show_default=True, metavar="MM", help=f"Tatami row spacing, in {ROW_SPACING.range_text} mm.")
@click.option("--underlay/--no-underlay", default=True, show_default=True,
              help="Underlay where it fits: centre walk (satin), edge run or tatami underlay.")
@click.option("--travel", type=click.Choice(TRAVELS), default="stitch", show_default=True,
              help="Between neighbouring pieces: a running stitch across the gap, a jump (a "
                   "float to clip by hand) or a trim; electrodes are always stitched.")
@click.option("--pull-compensation", "pull_compensation_mm", type=options.BoundedFloat(0.0, 1.0),
              default=0.1, show_default=True, metavar="MM",
              help="Row ends lengthened by this against the knit's pull-in (at most a quarter "
                   "of the gap to the next piece).")
@click.option("--output", "-o", type=options.OutputFile(as_str=True), required=True, metavar="FILE",
              help="Embroidery file to write; its extension names the format (.jef, .dst, "
                   ".pes; .exp and .vp3 experimental).")
@click.option("--preview", "preview_path", type=options.OutputFile((".png", ".svg"), as_str=True),
              default=None, metavar="FILE",
              help="Also write a stitch-plan preview (.png or .svg), together with -o: both or "
                   "neither.")
def patch(diameter_mm, fill, resolution_mm, conductive, core, outline, fmt, hoop, row_spacing_mm,
          underlay, travel, pull_compensation_mm, output, preview_path):
    """Write the embroidery file of one patch (hoop coordinates, centre at 0,0): circular, or
    composite (--core) with an optional non-circular outline (--outline)."""
    fmt_name = export.get_format(fmt).name if fmt else export.format_from_path(output).name
    hoop_obj = default_machine().choose_hoop(diameter_mm, diameter_mm, hoop, margin=True)
    outputs = {"--output": output, "--preview": preview_path}
    check_distinct(outputs)
    if core is None and outline is None:
        selection = parse_selection(conductive) if conductive else None
        geom = make_patch(diameter_mm, fill, resolution_mm, selection)
    else:
        geom = geometry_for(_spec(diameter_mm, fill, conductive, core, outline), resolution_mm)
    if conductive and not geom.conductive.any():
        raise InvalidInputError(f"--conductive {conductive!r} selects no triangle of this patch "
                                f"({geom.n_triangles} triangles)")
    prm = StitchParams(row_spacing_mm=row_spacing_mm, underlay=underlay, travel=travel,
                       pull_compensation_mm=pull_compensation_mm)
    plan = plan_stitches(geom, prm)
    threads = audit(plan, geom.pieces_mm, geom.conductive, geom.centroids_mm, resolution_mm,
                    prm.min_stitch_mm)
    _, gap = feature_sizes(geom)
    min_gap = CheckLimits().min_gap_mm
    with together(outputs) as tmp:
        export.write(tmp["--output"], plan, fmt_name, hoop_obj, label=_label(output))
        if preview_path:
            preview.write_preview(tmp["--preview"], plan, diameter_mm)
    rows = [
        ("design", f"d = {diameter_mm:g} mm, fill = {fill:g}, resolution = {resolution_mm:g} mm"),
        ("triangles", f"{geom.n_triangles} ({int(geom.conductive.sum())} conductive)"),
        ("fill", f"{geom.achieved_fill:.4f} (scale {geom.scale:.4f})" if core is None else
                 f"{geom.achieved_fill:.4f} overall (surround {fill:g}, core {core.split(',')[1]})"),
        ("stitches", str(plan.stitch_count)),
        ("trims", str(plan.trim_count)),
        ("gap crossings", f"{threads.gap_crossings} ({threads.gap_crossing_mm:.1f} mm of thread "
                          f"over unstitched fabric; --travel {travel})"),
        ("electrodes", ", ".join(f"{c} thread(s)" for c in threads.electrode_components)
                       or "none"),
    ] + _thread_rows(plan, output) + [
        ("thread", f"{plan.thread_length_mm / 1000:.2f} m"),
        ("time", f"{plan.sewing_time_min:.1f} min at {plan.stitches_per_minute:g} stitches/min, "
                 f"{plan.trim_s:g} s per trim, {plan.colour_change_s:g} s per colour change"),
        ("hoop", str(hoop_obj)),
        ("file", f"{output} ({fmt_name})"),
    ] + [("note", n) for n in plan.fabrication_notes()[len(plan.threads):]]
    if gap is not None and gap < min_gap - 1e-9:
        shown = f"{gap:.2f}" if round(gap, 2) < min_gap else f"{gap:.3f}"
        rows.append(("warning", f"gaps of {shown} mm between triangles are narrower than "
                                f"{min_gap:g} mm (the check's feature-gap rule) and may close "
                                "up: a coarser resolution widens them"))
    if fmt_name in export.EXPERIMENTAL:
        rows.append(("warning", f"{fmt_name.upper()} is experimental: its trims are not "
                                "checked by an independent decoder"))
    click.echo(key_value_table(rows))


def _thread_rows(plan, output) -> list[tuple[str, str]]:
    """One row per thread block: its role and, for a JEF file, the palette thread the machine
    shows for it (``jef_palette``), else the colour the file carries."""
    from stitchswitch.layout.embroidery.jef_palette import is_jef, machine_thread_text

    rgbs = [t.rgb for t in plan.threads]
    shown = (machine_thread_text(rgbs) if is_jef(output)
             else ["#%02x%02x%02x" % c for c in rgbs])
    return [(f"thread {k}", f"{t.name}: {text}")
            for k, (t, text) in enumerate(zip(plan.threads, shown), start=1)]


def _label(output) -> str:
    """The design label in the file header: the output file's name without its extension."""
    import pathlib
    return pathlib.Path(output).stem


def _numbers(text: str, what: str) -> list[float]:
    try:
        return [float(v) for v in text.split(",")]
    except ValueError:
        raise InvalidInputError(f"{what}: {text!r} is not a list of numbers") from None


def _spec(diameter_mm, fill, conductive, core, outline) -> PatchSpec:
    composite = None
    if core is not None:
        values = _numbers(core, "--core")
        if len(values) != 2:
            raise InvalidInputError(f"--core: {core!r} is not D,P (e.g. 20,1.0)")
        if not 0.0 < values[1] <= 1.0:
            raise InvalidInputError(f"--core: fill {values[1]:g} is outside (0, 1]")
        composite = CompositeSpec(values[0], values[1])
    points = None
    if outline is not None:
        points = [_numbers(p, "--outline") for p in outline.split(";") if p.strip()]
        if any(len(p) != 2 for p in points):
            raise InvalidInputError(f"--outline: {outline!r} is not X,Y;X,Y;...")
    return PatchSpec("patch", "", (0.0, 0.0), diameter_mm, fill, composite=composite,
                     outline_mm=points, conductive=conductive)
