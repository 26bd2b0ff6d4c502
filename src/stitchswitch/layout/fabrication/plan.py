"""The stitch plan of one hooping: every patch's stitches in hoop coordinates, grouped by thread.

Each patch's geometry (``patch_design.geometry_for``, centred at the origin, stretched mm) is
turned with the hoop (a hoop turned by 90 degrees on the piece sees the piece turned by -90)
and moved to the patch's position in hoop coordinates. Sewing order: one block per thread
colour, top threads first, then conductive threads (each colour change is one ``COLOR_CHANGE``
record); inside a block the patches in the hooping's order (``order``), each patch's
triangles in ``stitches.plan_stitches`` order. A patch with conductive triangles therefore
adds a colour change: the conductive block, which the paper sews with conductive thread in the
bobbin (section 6, Fig. 13).
"""
from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from stitchswitch.errors import StitchSwitchError
from stitchswitch.layout.embroidery import stitches as st
from stitchswitch.layout.embroidery.planar import transform
from stitchswitch.layout.fabrication.grouping.result import Hooping


@dataclass(frozen=True)
class ThreadUse:
    role: str            # "top" or "conductive"
    colour: str          # "#rrggbb"
    patches: tuple[str, ...]


@dataclass(frozen=True, eq=False)
class HoopingPlan:
    plan: st.StitchPlan
    threads: tuple[ThreadUse, ...]
    geometries: dict          # patch id -> geometry in hoop axes, centred at the origin


def _rgb(hex_colour: str) -> tuple[int, int, int]:
    h = hex_colour.lstrip("#")
    return int(h[0:2], 16), int(h[2:4], 16), int(h[4:6], 16)


def turned(geom, axes: np.ndarray):
    """The geometry in hoop axes (rows of ``axes``: the hoop's x and y in piece coordinates)."""
    if np.allclose(axes, np.eye(2)):
        return geom
    rot = lambda p: transform(p, axes.T)  # noqa: E731
    return replace(geom, centroids_mm=rot(geom.centroids_mm),
                   pieces_mm=tuple(rot(p) for p in geom.pieces_mm))


def _subset(geom, mask: np.ndarray):
    idx = np.flatnonzero(mask)
    changes = dict(centroids_mm=geom.centroids_mm[idx],
                   pieces_mm=tuple(geom.pieces_mm[i] for i in idx),
                   conductive=np.zeros(len(idx), dtype=bool),
                   areas_mm2=np.asarray(geom.areas_mm2)[idx])
    if getattr(geom, "piece_scale", None) is not None:
        changes["piece_scale"] = np.asarray(geom.piece_scale)[idx]
    return replace(geom, **changes)


def _concat(plans, threads, spm: float) -> st.StitchPlan:
    xy, cmd = [], []
    last_thread = None
    for thread_index, plan in plans:
        if last_thread is not None and thread_index != last_thread:
            xy.append(xy[-1])
            cmd.append(st.COLOR_CHANGE)
        keep = plan.commands != st.END
        xy += list(plan.xy_mm[keep])
        cmd += list(plan.commands[keep])
        last_thread = thread_index
    xy.append(xy[-1] if xy else np.zeros(2))
    cmd.append(st.END)
    return st.StitchPlan(np.asarray(xy, dtype=float).reshape(-1, 2), np.asarray(cmd, dtype=np.int8),
                         tuple(threads), spm,
                         small_pieces=sum(plan.small_pieces for _, plan in plans))


def plan_hooping(hooping: Hooping, specs: dict, geometry, prm: st.StitchParams | None = None
                 ) -> HoopingPlan:
    """The stitch plan of ``hooping``. ``specs``: patch id -> ``PatchSpec``; ``geometry``:
    spec -> ``PatchGeometry`` (``patch_design.geometry_for``, possibly cached)."""
    prm = prm or st.StitchParams()
    axes = hooping.axes()
    geoms = {pid: turned(geometry(specs[pid]), axes) for pid in hooping.patch_ids}
    blocks: dict[tuple[str, str], list[str]] = {}
    for role in ("top", "conductive"):
        for pid in hooping.patch_ids:
            mask = geoms[pid].conductive if role == "conductive" else ~geoms[pid].conductive
            if np.any(mask):
                colour = getattr(specs[pid].threads, role).lower()
                blocks.setdefault((role, colour), []).append(pid)
    uses, threads, plans = [], [], []
    pos = dict(zip(hooping.patch_ids, hooping.positions_mm))
    for k, ((role, colour), pids) in enumerate(blocks.items()):
        uses.append(ThreadUse(role, colour, tuple(pids)))
        name = f"{'conductive' if role == 'conductive' else 'top'} thread {colour}"
        threads.append(st.Thread(name, _rgb(colour)))
        for pid in pids:
            g = geoms[pid]
            sub = _subset(g, g.conductive if role == "conductive" else ~g.conductive)
            plans.append((k, st.plan_stitches(sub, prm, pos[pid])))
    plan = _concat(plans, threads, prm.stitches_per_minute)
    _check_inside(plan, hooping)
    return HoopingPlan(plan, tuple(uses), geoms)


def audit_hooping(hplan: HoopingPlan, hooping: Hooping, resolution_mm: float,
                  min_stitch_mm: float):
    """The stitch audit (``sewing.audit``) of a hooping's plan over all its patches' triangles
    in hoop coordinates: gap crossings, trims, short stitches, electrodes."""
    from stitchswitch.layout.embroidery.sewing.audit import audit

    pieces, conductive, centroids = [], [], []
    for pid, xy in zip(hooping.patch_ids, hooping.positions_mm):
        g = hplan.geometries[pid]
        off = np.asarray(xy, dtype=float)
        pieces += [np.asarray(p, dtype=float) + off for p in g.pieces_mm]
        conductive.append(np.asarray(g.conductive, dtype=bool))
        centroids.append(np.asarray(g.centroids_mm, dtype=float).reshape(-1, 2) + off)
    return audit(hplan.plan, pieces, np.concatenate(conductive), np.concatenate(centroids),
                 resolution_mm, min_stitch_mm)


def _check_inside(plan: st.StitchPlan, hooping: Hooping) -> None:
    x0, y0, x1, y1 = plan.extents_mm()
    w, h = hooping.hoop.width_mm, hooping.hoop.height_mm
    if x0 < -w / 2 - 1e-6 or x1 > w / 2 + 1e-6 or y0 < -h / 2 - 1e-6 or y1 > h / 2 + 1e-6:
        raise StitchSwitchError(f"internal error: the stitches of a hooping leave the "
                                f"{hooping.hoop} field ({x0:.1f}, {y0:.1f}) - ({x1:.1f}, {y1:.1f}) mm")
