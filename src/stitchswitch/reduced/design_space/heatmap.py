"""The h(d, p) heatmap of a design map, like the paper's Fig. 4 (left), as a PNG."""
from __future__ import annotations

import numpy as np

from stitchswitch.files.atomic import atomic_write_bytes
from stitchswitch.files.figures import plot_bytes
from stitchswitch.reduced.design_space.design_map import FLAG_NAMES, FLAG_SMOOTH, DesignMap

_MARKERS = {"branch change": ("x", "black"), "buckling onset": ("o", "white"),
            "under-resolved": ("s", "grey"), "unexplained": ("X", "red")}


def plot_height_map(dmap: DesignMap, path, points=None, title: str | None = None) -> None:
    """Write the heatmap to ``path`` (atomically). Flagged grid points are marked by kind;
    ``points`` (optional dict of label -> (d array, p array)) are overlaid as data."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    d, p = dmap.diameter_mm, dmap.fill
    fig, ax = plt.subplots(figsize=(7.5, 5.0), dpi=120)
    mesh = ax.pcolormesh(d, p, dmap.h_mm.T, shading="nearest", cmap="viridis")
    fig.colorbar(mesh, ax=ax, label="predicted height h (mm)")
    levels = [lv for lv in (1, 5, 10, 15, 20, 25) if dmap.h_mm.min() < lv < dmap.h_mm.max()]
    if levels:
        cs = ax.contour(d, p, dmap.h_mm.T, levels=levels, colors="white", linewidths=0.6)
        ax.clabel(cs, fmt="%g mm", fontsize=7)
    for code, name in FLAG_NAMES.items():
        if code == FLAG_SMOOTH:
            continue
        i, j = np.nonzero(dmap.flags == code)
        if i.size:
            marker, color = _MARKERS[name]
            ax.scatter(d[i], p[j], marker=marker, s=14, c=color, linewidths=0.8,
                       label=f"{name} ({i.size})")
    for label, (pd, pp) in (points or {}).items():
        ax.scatter(pd, pp, s=22, edgecolors="black", linewidths=0.6, label=label)
    ax.set_xlabel("patch diameter d (mm, on the pre-stretched fabric)")
    ax.set_ylabel("fill fraction p")
    ax.set_title(title or f"Reduced model: h(d, p), material {dmap.material_hash[:10]}")
    if ax.get_legend_handles_labels()[0]:
        ax.legend(loc="lower right", fontsize=7, framealpha=0.8)
    fig.tight_layout()
    atomic_write_bytes(path, plot_bytes(fig))
