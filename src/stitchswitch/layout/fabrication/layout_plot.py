"""Hooping layouts (PNG or SVG), like the paper's Fig. 11: one figure per hooping and an overview.

A hooping figure is in hoop coordinates (mm, origin at the field centre, x along the hoop's
width): the frame ring (grey band), the sewing field (solid) and the margin line (dashed), the
stitched triangles of this hooping's patches in their thread colours with their ids and sewing
order, and the alignment marks: a centre cross and a notch at the middle of every field side,
where hoop templates carry their marks. In garment mode the stretched piece is drawn behind,
with the patches of other hoopings: filled grey if already stitched, dotted if still to come,
red where this hooping's frame lands on a stitched one (an unavoidable conflict).

The overview shows, in garment mode, every stretched piece with all patches and the numbered
hoop fields and frames; in free mode every hooping's field side by side. Output is
deterministic (fixed SVG hash salt, no dates).
"""
from __future__ import annotations

import numpy as np

from stitchswitch.errors import InvalidInputError
from stitchswitch.files.figures import NO_STAMP, plot_bytes
from stitchswitch.layout.embroidery.planar import transform


def _pyplot():
    import matplotlib
    matplotlib.use("Agg", force=False)
    import matplotlib.pyplot as plt
    return plt


#: metadata that would make the bytes depend on the day or the library build, left out
def _save(fig, formats) -> dict[str, bytes]:
    """The figure in every format of ``formats`` (png, svg, pdf); the figure is closed."""
    out = {}
    try:
        for fmt in formats:
            if fmt not in NO_STAMP:
                raise InvalidInputError(f"unsupported layout format {fmt!r}; supported: "
                                        + ", ".join(NO_STAMP))
            out[fmt] = plot_bytes(fig, fmt, close=False, dpi=120)
    finally:
        _pyplot().close(fig)
    return out


def _rect(ax, w, h, **kw):
    from matplotlib.patches import Rectangle
    ax.add_patch(Rectangle((-w / 2, -h / 2), w, h, fill=False, **kw))


def _frame(ax, hoop):
    from matplotlib.patches import PathPatch
    from matplotlib.path import Path
    w, h = hoop.width_mm, hoop.height_mm
    ow, oh = w + 2 * hoop.frame_width_mm, h + 2 * hoop.frame_width_mm
    outer = [(-ow / 2, -oh / 2), (ow / 2, -oh / 2), (ow / 2, oh / 2), (-ow / 2, oh / 2), (0, 0)]
    inner = [(-w / 2, -h / 2), (-w / 2, h / 2), (w / 2, h / 2), (w / 2, -h / 2), (0, 0)]
    codes = [Path.MOVETO, Path.LINETO, Path.LINETO, Path.LINETO, Path.CLOSEPOLY] * 2
    ax.add_patch(PathPatch(Path(outer + inner, codes), facecolor="0.6", alpha=0.35,
                           edgecolor="0.4", lw=0.6, zorder=1))
    _rect(ax, w, h, edgecolor="black", lw=1.0, zorder=3)
    uw, uh = hoop.usable_mm()
    _rect(ax, uw, uh, edgecolor="0.3", lw=0.6, ls="--", zorder=3)


def alignment_marks(hoop) -> list[tuple[float, float]]:
    """Hoop coordinates of the marks: the centre and the middle of every field side."""
    w, h = hoop.width_mm, hoop.height_mm
    return [(0.0, 0.0), (w / 2, 0.0), (0.0, h / 2), (-w / 2, 0.0), (0.0, -h / 2)]


def _marks(ax, hoop):
    w, h = hoop.width_mm, hoop.height_mm
    s = 0.04 * min(w, h)
    ax.plot([-s, s], [0, 0], color="#c0392b", lw=1.0, zorder=6)
    ax.plot([0, 0], [-s, s], color="#c0392b", lw=1.0, zorder=6)
    tri = np.array([[-s / 2, 0], [s / 2, 0], [0, -s]])
    for (x, y), ang in zip(alignment_marks(hoop)[1:], (-90, 0, 90, 180)):   # point inwards
        a = np.radians(ang)
        rot = np.array([[np.cos(a), -np.sin(a)], [np.sin(a), np.cos(a)]])
        p = transform(tri, rot.T) + [x, y]
        ax.fill(p[:, 0], p[:, 1], color="#c0392b", lw=0, zorder=6)


def _rgb(c: str):
    c = c.lstrip("#")
    return tuple(int(c[i:i + 2], 16) / 255.0 for i in (0, 2, 4))


def _disc(ax, xy, d, **kw):
    from matplotlib.patches import Circle
    ax.add_patch(Circle(xy, d / 2, **kw))


def _hooping_legend(ax, garment: bool) -> None:
    """A legend of the figure's marks, below the axes (the sheet's legend says more)."""
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch
    handles = [Patch(fc="0.6", alpha=0.35, ec="0.4", label="hoop frame (clamps)"),
               Line2D([], [], color="black", lw=1.0, label="sewing field"),
               Line2D([], [], color="0.3", lw=0.6, ls="--", label="margin (no stitches)"),
               Line2D([], [], color="#c0392b", marker="+", ls="none", markersize=9,
                      label="centre and side marks"),
               Patch(fc="#7f8c99", label="n. id: patches, sewing order")]
    if garment:
        handles += [Patch(fc="0.7", ec="0.4", label="stitched earlier"),
                    Line2D([], [], color="0.45", ls=":", label="stitched later"),
                    Patch(fc="#f5b7b1", ec="#c0392b", label="frame on a stitched patch")]
    ax.legend(handles=handles, loc="upper center", bbox_to_anchor=(0.5, -0.09), ncol=3,
              fontsize=6, frameon=False)


def hooping_figure(k: int, total: int, hooping, hplan, specs, feet, pieces, stitched_before,
                   conflict_ids, formats=("png", "svg")) -> dict[str, bytes]:
    """The layout of hooping ``k`` (1-based) of ``total``: format -> bytes (PNG, SVG)."""
    from matplotlib.collections import PolyCollection
    plt = _pyplot()
    import matplotlib
    hoop = hooping.hoop
    ow, oh = hoop.width_mm + 2 * hoop.frame_width_mm, hoop.height_mm + 2 * hoop.frame_width_mm
    with matplotlib.rc_context({"svg.hashsalt": "stitchswitch", "svg.fonttype": "none"}):
        fig, ax = plt.subplots(figsize=(6.4, 1.2 + 6.0 * min(1.6, max(0.6, oh / ow))))
        if hooping.piece is not None:
            piece = next(p for p in pieces if p.name == hooping.piece)
            outline = hooping.to_hoop(piece.outline_mm)
            ax.fill(outline[:, 0], outline[:, 1], color="#eef3f8", lw=0.8, ec="#7f8c99", zorder=0)
            for f in feet:
                if f.piece != hooping.piece or f.id in hooping.patch_ids:
                    continue
                c = hooping.to_hoop(np.array([f.centre_mm]))[0]
                if f.id in conflict_ids:
                    _disc(ax, c, f.diameter_mm, fc="#f5b7b1", ec="#c0392b", lw=1.0, zorder=2)
                elif f.id in stitched_before:
                    _disc(ax, c, f.diameter_mm, fc="0.7", ec="0.4", lw=0.5, zorder=2)
                else:
                    _disc(ax, c, f.diameter_mm, fill=False, ec="0.45", lw=0.6, ls=":", zorder=2)
        _frame(ax, hoop)
        polys, colours = [], []
        for n, (pid, (x, y)) in enumerate(zip(hooping.patch_ids, hooping.positions_mm), start=1):
            g, spec = hplan.geometries[pid], specs[pid]
            for piece_xy, cond in zip(g.pieces_mm, g.conductive):
                polys.append(np.asarray(piece_xy) + [x, y])
                colours.append(_rgb(spec.threads.conductive if cond else spec.threads.top))
            _disc(ax, (x, y), spec.diameter_mm, fill=False, ec="0.35", lw=0.5, ls="--", zorder=3)
            ax.annotate(f"{n}. {pid}", (x, y + spec.diameter_mm / 2), ha="center", va="bottom",
                        fontsize=7, zorder=5)
        ax.add_collection(PolyCollection(polys, facecolors=colours, edgecolors="none", zorder=4))
        _marks(ax, hoop)
        _hooping_legend(ax, hooping.piece is not None)
        pad = 0.04 * max(ow, oh)
        ax.set_xlim(-ow / 2 - pad, ow / 2 + pad)
        ax.set_ylim(-oh / 2 - pad, oh / 2 + pad)
        ax.set_aspect("equal")
        ax.set_xlabel("x (mm, hoop)")
        ax.set_ylabel("y (mm, hoop)")
        turned = ", turned 90 deg" if hooping.orientation_deg == 90 else ""
        where = f" on {hooping.piece}" if hooping.piece else ""
        ax.set_title(f"Hooping {k}/{total}: {hoop}{turned}{where}\n{len(hooping.patch_ids)} "
                     f"patch(es), {hplan.plan.stitch_count} stitches", fontsize=9)
        fig.tight_layout()
        return _save(fig, formats)


def overview_figure(hoopings, feet, pieces, formats=("png", "svg")) -> dict[str, bytes]:
    """All hoopings: on the stretched pieces (garment mode) or side by side (free mode)."""
    from matplotlib.patches import Polygon
    plt = _pyplot()
    import matplotlib
    garment = hoopings[0].piece is not None
    panels = [p for p in pieces if any(h.piece == p.name for h in hoopings)] if garment \
        else list(hoopings)
    cmap = matplotlib.colormaps["tab10"]
    with matplotlib.rc_context({"svg.hashsalt": "stitchswitch", "svg.fonttype": "none"}):
        fig, axes = plt.subplots(1, len(panels), figsize=(min(16.0, 4.5 * len(panels)), 5.5),
                                 squeeze=False)
        for ax, panel in zip(axes[0], panels):
            if garment:
                ax.fill(panel.outline_mm[:, 0], panel.outline_mm[:, 1], color="#eef3f8",
                        ec="#7f8c99", lw=0.8)
                for f in feet:
                    if f.piece == panel.name:
                        _disc(ax, f.centre_mm, f.diameter_mm, fc="0.55", ec="0.3", lw=0.4)
                for k, h in enumerate(hoopings, start=1):
                    if h.piece != panel.name:
                        continue
                    col = cmap((k - 1) % 10)
                    for (w, hh), ls, lw in ((h.hoop.field_mm(0), "-", 1.2),
                                            (h.hoop.outer_mm(0), ":", 0.8)):
                        corners = np.array([[-w / 2, -hh / 2], [w / 2, -hh / 2],
                                            [w / 2, hh / 2], [-w / 2, hh / 2]])
                        ax.add_patch(Polygon(h.to_piece(corners), closed=True, fill=False,
                                             ec=col, ls=ls, lw=lw))
                    ax.annotate(str(k), h.centre_mm, color=col, fontsize=11, ha="center",
                                va="center", weight="bold")
                ax.set_title(f"piece {panel.name} (stretched)", fontsize=9)
                ax.set_xlabel("x (mm, stretched piece)", fontsize=8)
                ax.set_ylabel("y (mm, stretched piece)", fontsize=8)
            else:
                k = panels.index(panel) + 1
                _frame(ax, panel.hoop)
                for pid, (x, y) in zip(panel.patch_ids, panel.positions_mm):
                    d = next(f.diameter_mm for f in feet if f.id == pid)
                    _disc(ax, (x, y), d, fc="0.55", ec="0.3", lw=0.4)
                    ax.annotate(pid, (x, y), ha="center", va="center", fontsize=6)
                ax.set_title(f"{k}: {panel.hoop}", fontsize=9)
                ax.set_xlabel("x (mm, hoop)", fontsize=8)
                ax.set_ylabel("y (mm, hoop)", fontsize=8)
            ax.set_aspect("equal")
            ax.autoscale_view()
            ax.tick_params(labelsize=7)
        fig.suptitle(f"{len(hoopings)} hooping(s)" + (
            ": numbered fields (solid) and frames (dotted) in stitching order; grey: patches"
            if garment else ": patches (grey) in each hoop's field, frame band around it"),
            fontsize=9)
        fig.tight_layout()
        return _save(fig, formats)
