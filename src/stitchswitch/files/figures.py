"""``plot_bytes``: a matplotlib figure as PNG, SVG or PDF bytes with no date or software stamp,
so the same figure gives the same bytes on every run (the files the package writes are
byte-reproducible); the figure is closed afterwards, whatever happens.
"""
from __future__ import annotations

import io

__all__ = ["NO_STAMP", "plot_bytes"]

#: The metadata entries that would otherwise carry a date or matplotlib's version, per format.
NO_STAMP = {"png": {"Software": None}, "svg": {"Date": None},
            "pdf": {"CreationDate": None, "Producer": None, "Creator": None}}


def plot_bytes(fig, fmt: str = "png", *, close: bool = True, **savefig_kwargs) -> bytes:
    """``fig`` saved as ``fmt`` (png, svg or pdf) without stamps; ``savefig_kwargs`` go to
    ``Figure.savefig`` (dpi, bbox_inches, ...). ``close=False`` keeps the figure open for
    another format."""
    if fmt not in NO_STAMP:
        raise ValueError(f"unsupported figure format {fmt!r}; supported: {', '.join(NO_STAMP)}")
    try:
        buf = io.BytesIO()
        fig.savefig(buf, format=fmt, metadata=NO_STAMP[fmt], **savefig_kwargs)
        return buf.getvalue()
    finally:
        if close:
            import matplotlib.pyplot as plt

            plt.close(fig)
