"""The force-displacement curve of a switching path (``path.SwitchingPath``) as a PNG: contact
force in newtons against the plate height w (axis inverted, the plate travels downwards), the
switching force as a dashed line, the design and the verdict in the title.

Drawn with matplotlib's Agg backend, offscreen, with no ``Software`` entry in the PNG's
metadata, so the same curve gives byte-identical files; ``write_curve_png`` writes it
atomically (``files.atomic``).
"""
from __future__ import annotations

from stitchswitch.files.atomic import atomic_write_bytes
from stitchswitch.files.figures import plot_bytes

__all__ = ["curve_png", "write_curve_png"]


def curve_png(curve, verdict: str) -> bytes:
    """The curve drawn as PNG bytes; ``verdict``: the design's bistability verdict
    (``states.bistability``), stated in the title."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    patch = curve.patch
    fig, ax = plt.subplots(figsize=(6, 4), dpi=120)
    ax.plot(curve.w_mm, curve.force * curve.newton_per_n, "o-", ms=3)
    ax.axhline(curve.switching_force_n, color="k", lw=0.5, ls="--")
    ax.set_xlabel("plate height w (mm)")
    ax.set_ylabel("contact force (N)")
    ax.set_title(f"d = {patch.diameter_mm:g} mm, p = {patch.fill:g}: switching force "
                 f"{curve.switching_force_n:.3g} N ({verdict})")
    ax.invert_xaxis()
    ax.grid(alpha=0.3)
    fig.tight_layout()
    return plot_bytes(fig)


def write_curve_png(path, curve, verdict: str) -> None:
    """``curve_png`` written to ``path`` atomically."""
    atomic_write_bytes(path, curve_png(curve, verdict))
