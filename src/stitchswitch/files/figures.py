"""``plot_bytes``: a matplotlib figure as PNG, SVG or PDF bytes with no date or software stamp
and, in SVG, element ids from a fixed salt (``SVG_SALT``) instead of random ones, so the same
figure gives the same bytes on every run (the files the package writes are byte-reproducible);
the figure is closed afterwards, whatever happens.
"""
from __future__ import annotations

import io

__all__ = ["NO_STAMP", "SVG_SALT", "plot_bytes"]

#: The salt of the SVG element ids (matplotlib's ``svg.hashsalt``; random when unset).
SVG_SALT = "stitchswitch"

#: The metadata entries that would otherwise carry a date or matplotlib's version, per format.
NO_STAMP = {"png": {"Software": None}, "svg": {"Date": None},
            "pdf": {"CreationDate": None, "Producer": None, "Creator": None}}


def plot_bytes(fig, fmt: str = "png", *, close: bool = True, **savefig_kwargs) -> bytes:
    """``fig`` saved as ``fmt`` (png, svg or pdf) without stamps; ``savefig_kwargs`` go to
    ``Figure.savefig`` (dpi, bbox_inches, ...). ``close=False`` keeps the figure open for
    another format."""
    if fmt not in NO_STAMP:
        raise ValueError(f"unsupported figure format {fmt!r}; supported: {', '.join(NO_STAMP)}")
    import matplotlib

    try:
        buf = io.BytesIO()
        with matplotlib.rc_context({"svg.hashsalt": SVG_SALT}):
            fig.savefig(buf, format=fmt, metadata=NO_STAMP[fmt], **savefig_kwargs)
        return buf.getvalue()
    finally:
        if close:
            import matplotlib.pyplot as plt

            plt.close(fig)
