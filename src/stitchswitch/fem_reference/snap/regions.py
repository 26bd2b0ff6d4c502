"""The bistability map: bistable, spring-back or flat over a grid of designs (d, p), for one
natural curvature of the embroidered layer (``stitchswitch bistability-map``).

Each cell is ``states.bistability``: the pop-up state in the frame and its relaxed mirror image.
A cell whose pop-up or relaxed state is not certified (Newton did not converge to a strict
minimum) is reported as "uncertain", never guessed.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from stitchswitch.fem_reference.revolution.params import DEFAULT_SHELL, ShellParams
from stitchswitch.fem_reference.snap.states import bistability
from stitchswitch.files.figures import plot_bytes
from stitchswitch.reduced.model.params import DEFAULT_MATERIAL, Material, Patch

VERDICTS = ("flat", "spring-back", "bistable", "uncertain")


def cell_verdict(b) -> str:
    if not b.popup.certified:
        return "uncertain"
    if b.popped and not b.inverted.certified:
        return "uncertain"
    return b.verdict


@dataclass(frozen=True)
class BistabilityMap:
    diameters_mm: tuple
    fills: tuple
    kappa0_per_mm: float
    verdicts: tuple          # verdicts[i][j] at diameters_mm[i], fills[j]

    def as_dict(self) -> dict:
        return {"d_mm": list(self.diameters_mm), "fill": list(self.fills),
                "kappa0_per_mm": self.kappa0_per_mm, "verdicts": [list(r) for r in self.verdicts]}

    def counts(self) -> dict:
        flat = [v for row in self.verdicts for v in row]
        return {v: flat.count(v) for v in VERDICTS}


def bistability_map(diameters_mm, fills, material: Material = DEFAULT_MATERIAL,
                    params: ShellParams = DEFAULT_SHELL) -> BistabilityMap:
    rows = []
    for d in diameters_mm:
        rows.append(tuple(cell_verdict(bistability(Patch(float(d), float(p)), material, params))
                          for p in fills))
    return BistabilityMap(tuple(float(d) for d in diameters_mm), tuple(float(p) for p in fills),
                          params.kappa0_per_mm, tuple(rows))


def map_png(result: BistabilityMap) -> bytes:
    """The regions drawn over (d, p) as PNG bytes (matplotlib, offscreen)."""

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.colors import ListedColormap

    code = np.array([[VERDICTS.index(v) for v in row] for row in result.verdicts], dtype=float)
    fig, ax = plt.subplots(figsize=(6, 4), dpi=110)
    cmap = ListedColormap(["#d9d9d9", "#fdae61", "#2c7bb6", "#ffffff"])
    d, p = np.array(result.diameters_mm), np.array(result.fills)
    ax.pcolormesh(_edges(d), _edges(p), code.T, cmap=cmap, vmin=-0.5, vmax=3.5, edgecolors="k",
                  linewidth=0.3)
    for k, name in enumerate(VERDICTS):
        ax.plot([], [], "s", color=cmap(k), mec="k", label=name)
    ax.legend(loc="upper left", fontsize=8)
    ax.set_xlabel("patch diameter d (mm)")
    ax.set_ylabel("fill p")
    ax.set_title(f"shell of revolution, natural curvature {result.kappa0_per_mm:g} /mm")
    fig.tight_layout()
    return plot_bytes(fig)


def _edges(x: np.ndarray) -> np.ndarray:
    if x.size == 1:
        return np.array([x[0] - 0.5, x[0] + 0.5])
    mid = 0.5 * (x[1:] + x[:-1])
    return np.concatenate([[2 * x[0] - mid[0]], mid, [2 * x[-1] - mid[-1]]])


def text_grid(result: BistabilityMap) -> str:
    mark = {"flat": ".", "spring-back": "S", "bistable": "B", "uncertain": "?"}
    lines = ["d_mm \\ p " + " ".join(f"{p:5.2f}" for p in result.fills)]
    for d, row in zip(result.diameters_mm, result.verdicts):
        lines.append(f"{d:9g} " + " ".join(f"{mark[v]:>5}" for v in row))
    lines.append("B bistable, S spring-back, . flat (no pop-up), ? uncertain (not certified)")
    return "\n".join(lines)
