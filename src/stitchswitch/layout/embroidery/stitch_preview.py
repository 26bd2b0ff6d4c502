"""Stitch-plan preview (SVG or PNG, by extension): stitches in their thread colours, jumps as
dashed grey lines, trims as black crosses, and the patch outline if given."""
from __future__ import annotations

import pathlib

import numpy as np

from stitchswitch.errors import InvalidInputError
from stitchswitch.files.atomic import atomic_write_bytes
from stitchswitch.files.figures import plot_bytes
from stitchswitch.layout.embroidery import stitches as st


def render(plan: st.StitchPlan, fmt: str = "png", diameter_mm: float | None = None) -> bytes:
    import matplotlib
    matplotlib.use("Agg", force=False)
    import matplotlib.pyplot as plt
    from matplotlib.collections import LineCollection

    if fmt not in ("png", "svg"):
        raise InvalidInputError(f"unsupported preview format {fmt!r}; supported: png, svg")
    with matplotlib.rc_context({"svg.hashsalt": "stitchswitch", "svg.fonttype": "none"}):
        fig, ax = plt.subplots(figsize=(6, 6))
        xy, cmd = plan.xy_mm, plan.commands
        colour = np.cumsum(cmd == st.COLOR_CHANGE)
        seg_st = {i: [] for i in range(len(plan.threads))}
        seg_jump = []
        for k in range(1, len(cmd)):
            if cmd[k] == st.STITCH and cmd[k - 1] != st.JUMP or (
                    cmd[k] == st.STITCH and np.allclose(xy[k], xy[k - 1])):
                seg_st[min(colour[k], len(plan.threads) - 1)].append((xy[k - 1], xy[k]))
            elif cmd[k] == st.JUMP:
                seg_jump.append((xy[k - 1], xy[k]))
        for i, segs in seg_st.items():
            rgb = np.asarray(plan.threads[i].rgb) / 255.0
            ax.add_collection(LineCollection(segs, colors=[rgb], linewidths=0.4,
                                             label=f"{plan.threads[i].name}"))
        if seg_jump:
            ax.add_collection(LineCollection(seg_jump, colors="0.6", linewidths=0.5,
                                             linestyles="dashed", label="jump"))
        trims = xy[cmd == st.TRIM]
        if len(trims):
            ax.plot(trims[:, 0], trims[:, 1], "kx", ms=3, mew=0.6, label="trim")
        if diameter_mm:
            t = np.linspace(0, 2 * np.pi, 361)
            ax.plot(diameter_mm / 2 * np.cos(t), diameter_mm / 2 * np.sin(t), color="0.8",
                    lw=0.5)
        ax.set_aspect("equal")
        ax.autoscale()
        ax.set_xlabel("x (mm, hoop)")
        ax.set_ylabel("y (mm, hoop)")
        ax.set_title(f"{plan.stitch_count} stitches, {plan.trim_count} trims, "
                     f"{len(plan.threads)} thread(s)")
        ax.legend(loc="upper right", fontsize=7)
        return plot_bytes(fig, fmt, dpi=200)


def write_preview(path, plan: st.StitchPlan, diameter_mm: float | None = None) -> None:
    fmt = pathlib.Path(path).suffix.lower().lstrip(".")
    atomic_write_bytes(path, render(plan, fmt, diameter_mm))
