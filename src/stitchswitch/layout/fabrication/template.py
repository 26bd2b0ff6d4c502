"""1:1 printable hooping templates (garment mode): per hooping a PDF, tiled on A4 or Letter,
to lay on the relaxed piece and mark through before stretching.

Everything is drawn in relaxed garment mm (the design's frame): the piece outline, the hoop's
sewing field and its outer frame as they land on the relaxed piece (hoop mm divided by eta, the
hoop turned as the hooping says), the centre cross and the four side marks
(``layout_plot.alignment_marks``), and the patches' relaxed footprints with their ids. The page
grid covers the frame's outline plus 10 mm; every tile has the same 1:1 scale (data mm = paper
mm inside a 10 mm page margin), its tile number, the axes coordinates, and a 50 mm calibration
square to check the printer did not scale the page ("print at 100 %").
"""
from __future__ import annotations

import io
import math

import numpy as np

from stitchswitch.layout.fabrication.hoop_outline import relaxed_outline
from stitchswitch.layout.fabrication.layout_plot import _pyplot

__all__ = ["PAPERS", "template_pdf"]

#: paper sizes, portrait (mm)
PAPERS = {"a4": (210.0, 297.0), "letter": (215.9, 279.4)}
MARGIN_MM = 10.0
CALIBRATION_MM = 50.0


def template_pdf(number: int, hooping, outline_mm, patches, eta: float, paper: str) -> bytes:
    """The template of hooping ``number`` as PDF bytes. ``outline_mm``: the relaxed piece;
    ``patches``: the hooping's ``PatchSpec`` records."""
    import matplotlib
    from matplotlib.backends.backend_pdf import PdfPages
    from matplotlib.patches import Circle, Polygon

    plt = _pyplot()
    pw, ph = PAPERS[paper]
    hoop = hooping.hoop
    fw, fh = hoop.width_mm, hoop.height_mm
    field, outer, marks = relaxed_outline(hooping, eta)
    lo, hi = outer.min(axis=0) - MARGIN_MM, outer.max(axis=0) + MARGIN_MM
    tw, th = pw - 2 * MARGIN_MM, ph - 2 * MARGIN_MM
    cols, rows = math.ceil((hi[0] - lo[0]) / tw), math.ceil((hi[1] - lo[1]) / th)
    cross = 0.06 * min(fw, fh) / eta
    buf = io.BytesIO()
    meta = {"CreationDate": None, "Producer": None, "Creator": None}
    with matplotlib.rc_context({"pdf.fonttype": 42}), PdfPages(buf, metadata=meta) as pdf:
        for r in range(rows):
            for c in range(cols):
                x0, y1 = lo[0] + c * tw, hi[1] - r * th          # tiles from the top left
                fig = plt.figure(figsize=(pw / 25.4, ph / 25.4))
                ax = fig.add_axes((MARGIN_MM / pw, MARGIN_MM / ph, tw / pw, th / ph))
                ax.set_xlim(x0, x0 + tw)
                ax.set_ylim(y1 - th, y1)
                ax.add_patch(Polygon(np.asarray(outline_mm), closed=True, fill=False,
                                     edgecolor="#333333", linewidth=0.8))
                ax.plot(*outer.T, color="#888888", linewidth=0.6, linestyle="--")
                ax.plot(*field.T, color="#1f5fa8", linewidth=1.0)
                for p in patches:
                    ax.add_patch(Circle(p.centre_mm, p.diameter_mm / (2 * eta), fill=False,
                                        edgecolor="#2e7d32", linewidth=0.6))
                    ax.text(*p.centre_mm, p.id, ha="center", va="center", fontsize=6)
                cx, cy = marks[0]
                ax.plot([cx - cross, cx + cross], [cy, cy], color="#c0392b", linewidth=0.8)
                ax.plot([cx, cx], [cy - cross, cy + cross], color="#c0392b", linewidth=0.8)
                ax.plot(marks[1:, 0], marks[1:, 1], "+", color="#c0392b", markersize=10)
                sx, sy = x0 + 5.0, y1 - th + 5.0
                ax.add_patch(Polygon([[sx, sy], [sx + CALIBRATION_MM, sy],
                                      [sx + CALIBRATION_MM, sy + CALIBRATION_MM],
                                      [sx, sy + CALIBRATION_MM]], closed=True, fill=False,
                                     edgecolor="black", linewidth=0.8))
                ax.text(sx + CALIBRATION_MM / 2, sy + CALIBRATION_MM / 2,
                        f"{CALIBRATION_MM:g} mm\nmeasure:\nprint at 100 %", ha="center",
                        va="center", fontsize=6)
                ax.tick_params(labelsize=5)
                ax.grid(True, linewidth=0.2, color="#cccccc")
                fig.text(0.5, 1 - 4 / ph, f"hooping {number}: {hoop}"
                         + (", turned 90" if hooping.orientation_deg == 90 else "")
                         + f"; relaxed piece, garment mm, 1:1; tile {r * cols + c + 1} of "
                         f"{rows * cols} (row {r + 1}, column {c + 1}); blue: sewing field, "
                         "dashed: frame, red: centre and side marks", ha="center", va="top",
                         fontsize=6)
                pdf.savefig(fig)
                plt.close(fig)
    return buf.getvalue()
