"""Build the design-space map: one certified solve per grid design, rows in parallel.

By default (``warm_start=True``) each row (one diameter) is solved along increasing fill, every
design started from the previous design's certified equilibrium (``solve(..., warm_start=)``;
a cold solve if there is none): the map holds the branch that continuation along increasing
fill reaches. That is the branch rule where two popped branches coexist (the dome and the
overhanging neck near the overhang onset): the sweep stays on the dome until the dome ends.
It is decided by continuation, not by round-off in a cold solve's path: a direct (cold)
solve agrees with the map except next to the dome's fold, where it may already land on the
neck, as its path decides (docs/design-map.md). With ``warm_start=False`` every point is
``solve(Patch(d, p), material)`` exactly, as a direct call makes it. Neighbours on the grid
are also used by ``map_check`` to explain any point that is not smooth (a branch change or the
buckling onset), by warm-starting one design from its neighbour's profile.
"""
from __future__ import annotations

import numpy as np

from stitchswitch.errors import InvalidInputError
from stitchswitch.executor import run_all
from stitchswitch.reduced.design_space.design_map import FLAG_SMOOTH, KEYPOINTS, DesignMap
from stitchswitch.reduced.model.params import DEFAULT_MATERIAL, Material, Patch

#: The most values ``parse_range`` gives for one axis of a map.
MAX_AXIS_POINTS = 2000
#: The default grid (the paper's Fig. 4 range): 86 diameters x 51 fills.
DEFAULT_DIAMETERS_MM = np.arange(15.0, 100.0 + 0.5, 1.0)
DEFAULT_FILLS = np.round(np.arange(0.50, 1.0 + 0.005, 0.01), 2)


def parse_range(text: str, name: str) -> np.ndarray:
    """'START:STOP:STEP' (inclusive of STOP when it falls on the grid) or one number."""
    parts = text.split(":")
    try:
        values = [float(x) for x in parts]
    except ValueError:
        raise InvalidInputError(f"{name}: {text!r} is not START:STOP:STEP") from None
    if len(values) == 1:
        return np.array(values)
    if len(values) != 3 or not np.all(np.isfinite(values)):
        raise InvalidInputError(f"{name}: {text!r} is not START:STOP:STEP")
    start, stop, step = values
    if step <= 0 or stop < start:
        raise InvalidInputError(f"{name}: {text!r} needs STEP > 0 and STOP >= START")
    n = int(np.floor((stop - start) / step + 1e-9)) + 1
    if n > MAX_AXIS_POINTS:
        raise InvalidInputError(f"{name}: {text!r} gives {n:.3g} values, at most {MAX_AXIS_POINTS} "
                                "are allowed per axis")
    return np.round(start + step * np.arange(n), 10)


def _sweep(d, fills, material, warm):
    """One solve per fill in the given order, each warm-started from the previous certified one."""
    from stitchswitch.reduced.solvers.solve import solve

    out, sol = [], None
    for p in fills:
        start = sol if warm and sol is not None and sol.converged else None
        sol = solve(Patch(d, p), material, warm_start=start)
        out.append(sol)
    return out


def _solve_row(args):
    d, fills, material, warm = args
    rows = {name: [] for name in KEYPOINTS + ("energy", "residual", "converged", "u", "z")}
    sols = _sweep(d, fills, material, warm)
    for sol in sols:
        kp = sol.keypoints
        for name in KEYPOINTS:
            rows[name].append(getattr(kp, name))
        rows["energy"].append(sol.energy)
        rows["residual"].append(sol.residual)
        rows["converged"].append(sol.certified)
        rows["u"].append((sol.r_mm - sol.R_mm).astype(np.float32))
        rows["z"].append(sol.z_mm.astype(np.float32))
    return rows, sols[-1].dr_mm, sols[-1].n_inside


def build(material: Material = DEFAULT_MATERIAL, diameters_mm=DEFAULT_DIAMETERS_MM,
          fills=DEFAULT_FILLS, workers: int = 1, progress=None, check: bool = True,
          scheduler: str | None = None, warm_start: bool = True) -> DesignMap:
    """Solve every grid design; ``progress(rows_done)`` is called once per diameter (local
    runs). ``scheduler``: a Dask scheduler address to solve the rows on a cluster.
    ``warm_start``: sweep each row along increasing fill from the previous equilibrium (the
    branch continuation reaches where two coexist; default); False: every point a cold solve.

    With ``check`` the smoothness test runs and unsmooth points are explained and flagged
    (``smoothness.classify``)."""
    from stitchswitch.reduced.model.material_io import material_hash

    d = np.asarray(diameters_mm, dtype=float)
    p = np.asarray(fills, dtype=float)
    for name, grid in (("diameters", d), ("fills", p)):
        if grid.ndim != 1 or grid.size < 2 or np.any(np.diff(grid) <= 0):
            raise InvalidInputError(f"{name}: need at least two increasing values, got {grid.tolist()}")
    for dd in d:                       # validate every design before any work
        for pp in (p[0], p[-1]):
            Patch(dd, pp)
    rows = run_all(_solve_row, [(float(x), p.tolist(), material, bool(warm_start)) for x in d],
                   workers, progress,
                   scheduler=scheduler)
    table = {k: np.array([r[0][k] for r in rows]) for k in rows[0][0]}
    dmap = DesignMap(
        diameter_mm=d, fill=p,
        **{k: table[k].astype(float) for k in KEYPOINTS},
        energy=table["energy"].astype(float), residual=table["residual"].astype(float),
        converged=table["converged"].astype(bool),
        u_mm=table["u"].astype(np.float32), z_prof_mm=table["z"].astype(np.float32),
        dr_mm=np.array([r[1] for r in rows]), n_inside=np.array([r[2] for r in rows]),
        material=material, material_hash=material_hash(material),
        flags=np.full((d.size, p.size), FLAG_SMOOTH, dtype=np.int8),
    )
    if check:
        from stitchswitch.reduced.design_space.smoothness import classify
        dmap = classify(dmap)
    return dmap
