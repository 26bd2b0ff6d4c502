"""``stitchswitch inverse``: designs that reach a target height (and radius)."""
from __future__ import annotations

import json

import click

from stitchswitch.cli import options, progress
from stitchswitch.reduced.design_space.inverse import HEIGHT_TOL_MM, InverseTarget, inverse_design


def for_machine(**kwargs):
    """The check's rules for an unplaced design (loaded only when inverse runs)."""
    from stitchswitch.layout.check import design_point
    return design_point.for_machine(**kwargs)


@click.command(cls=options.Command)
@click.option("--height", "height_mm", type=options.FINITE_FLOAT, required=True, metavar="MM",
              help="Target peak height h in mm.")
@options.inverse_target_opts()
@click.option("--force-range", type=(options.FINITE_FLOAT, options.FINITE_FLOAT), default=None,
              metavar="LO HI", help="Allowed switching force window in N.")
@click.option("--count", type=click.IntRange(min=1, max=50), default=5, show_default=True,
              metavar="N",
              help="Number of alternative designs.")
@options.material_opt
@click.option("--map", "map_path", type=click.Path(dir_okay=False), default=None, metavar="FILE",
              help="A design-space map from `stitchswitch precompute` (its material is used).")
@click.option("--rules/--no-rules", "rules", default=True, show_default=True,
              help="Leave out designs that break the check's fabrication rules (feature side "
                   "and gap at --resolution, hoop fit of the machine's roomiest hoop).")
@click.option("--resolution", "resolution_mm", type=options.FINITE_FLOAT, default=5.0,
              show_default=True, metavar="MM",
              help="Triangle side of the tessellation the feature rules judge.")
@options.json_opt
def inverse(height_mm, radius_mm, max_diameter_mm, min_fill, force_range, count, material_path,
            map_path, rules, resolution_mm, as_json):
    """Suggest distinct (d, fill) designs whose certified height meets the target.

    Candidates come from the design-space map, are chosen by a mixed-integer program (HiGHS)
    under the bounds, refined on the map and confirmed by direct solves. An unreachable target
    exits 2 with the achievable range. The map is the shipped one (default material), the one
    of --material (built once, about half a minute on 2 cores, then cached), or --map.
    """
    target = InverseTarget(height_mm, radius_mm, max_diameter_mm, min_fill,
                           tuple(force_range) if force_range else None, count)
    result = inverse_design(target, _map(material_path, map_path),
                            admissible=for_machine(resolution_mm=resolution_mm) if rules else None)
    cands = [c.as_dict() for c in result.candidates]
    if as_json:
        click.echo(json.dumps({
            "target": {"height_mm": height_mm, "radius_mm": radius_mm},
            "achievable_h_mm": list(result.achievable_h_mm),
            "selection": {"status": result.selection.status, "solver": "HiGHS",
                          "objective": result.selection.objective,
                          "solve_s": result.selection.solve_s, "mip_gap": result.selection.mip_gap},
            "fabrication_rules": rules, "dropped": list(result.dropped),
            "candidates": cands}))
        return
    if not cands:
        click.echo(f"no design within {HEIGHT_TOL_MM} mm of the target was confirmed")
        _why_fewer(result, count)
        return
    head = (f"{'#':>2} {'d_mm':>7} {'fill':>6} {'h_mm':>7} {'r_a_mm':>7} {'z_a_mm':>7} {'r_b_mm':>7} "
            f"{'z_b_mm':>7} {'force_N':>8}")
    click.echo(head)
    for k, c in enumerate(cands, 1):
        click.echo(f"{k:>2} {c['d_mm']:7.2f} {c['fill']:6.3f} {c['h_mm']:7.3f} {c['r_a_mm']:7.2f} "
                   f"{c['z_a_mm']:7.2f} {c['r_b_mm']:7.2f} {c['z_b_mm']:7.2f} {c['force_N']:8.3f}")
    click.echo(f"every row is a certified direct solve; selection: HiGHS {result.selection.status} "
               f"in {result.selection.solve_s:.2f} s")
    if any(c["force_extrapolated"] for c in cands):
        from stitchswitch.reduced.design_space.force_model import default_force_fit

        fit = default_force_fit()
        (d0, d1), (p0, p1) = fit.d_range_mm, fit.fill_range
        click.echo(f"force_N: the polynomial model of {fit.source.split('(')[0].strip() or 'the data'} "
                   f"data; rows outside its design range (d {d0:g}-{d1:g} mm, fill {p0:g}-{p1:g}) "
                   "are extrapolated")
    if len(cands) < count:
        _why_fewer(result, count)


def _why_fewer(result, count: int) -> None:
    click.echo(f"{len(result.candidates)} of {count} design(s) asked for: "
               + ("; ".join(result.dropped) or "no other design was found"))


def _map(material_path, map_path):
    from stitchswitch.errors import InvalidInputError
    from stitchswitch.reduced.design_space import cache as map_cache

    if material_path is not None and map_path is not None:
        raise InvalidInputError("give --material or --map, not both (a map carries its material)")
    if map_path is not None:
        from stitchswitch.reduced.design_space.storage import load_map

        return load_map(map_path)
    if material_path is None:
        return None
    from stitchswitch.reduced.model.material_io import load_material

    material = load_material(material_path)
    if material == map_cache.DEFAULT_MATERIAL:
        return None
    import os

    from stitchswitch.reduced.design_space.precompute import DEFAULT_DIAMETERS_MM

    with progress.bar(DEFAULT_DIAMETERS_MM.size,
                      "map of this material (built once, then cached)") as bar:
        done = [0]

        def advance(n):
            bar.update(n - done[0])
            done[0] = n
        return map_cache.map_for(material, workers=max(1, os.cpu_count() or 1), progress=advance)
