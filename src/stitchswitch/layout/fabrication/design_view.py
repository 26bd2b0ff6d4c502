"""The 2D layout of a design (paper, section 5, the layout view): pieces to scale with their
names, mm axes in the design's frame, every patch's footprint on the relaxed fabric (solid,
diameter d / eta) and on the stretched fabric (dashed, diameter d, drawn about the same centre
for scale) with its id, coloured by its predicted height h, and the check's violations marked
(a red ring and the rule's name next to the patch; pieces with a violation outlined red).

``design_view(design, heights_mm, violations, fmt) -> bytes``: ``heights_mm`` maps patch ids
to the predicted h (None: not predicted, drawn grey), computed by the caller (the design map or
a solve), so this module only draws. Same input, same bytes (no dates in the files).
"""
from __future__ import annotations

import numpy as np

from stitchswitch.layout.fabrication.layout_plot import _pyplot, _save

__all__ = ["design_view", "FORMATS"]

FORMATS = ("png", "svg", "pdf")


def design_view(design, heights_mm: dict, violations, fmt: str = "png") -> bytes:
    """The layout figure as ``fmt`` bytes (see the module docstring)."""
    import matplotlib
    from matplotlib.patches import Circle, Polygon

    plt = _pyplot()
    eta = float(design.material_object().eta)
    flagged: dict[str, list[str]] = {}
    bad_pieces = set()
    for v in violations:
        for pid in v.patches:
            flagged.setdefault(pid, []).append(v.rule)
        if v.severity == "error":
            bad_pieces.update(v.pieces)
    known = [h for h in heights_mm.values() if h is not None]
    h_max = max(known, default=1.0) or 1.0
    cmap = matplotlib.colormaps["viridis"]
    norm = matplotlib.colors.Normalize(0.0, h_max)
    with matplotlib.rc_context({"svg.hashsalt": "stitchswitch", "svg.fonttype": "none",
                                "pdf.fonttype": 42}):
        fig, ax = plt.subplots(figsize=(9, 7))
        for piece in design.pieces:
            ring = np.asarray(piece.outline_mm, dtype=float)
            bad = piece.name in bad_pieces
            ax.add_patch(Polygon(ring, closed=True, facecolor="#f3efe6",
                                 edgecolor="#c0392b" if bad else "#555555",
                                 linewidth=1.6 if bad else 1.0))
            cx, cy = ring.mean(axis=0)
            label = f"{piece.name}" + (f" (size {piece.size})" if piece.size else "")
            ax.text(cx, ring[:, 1].max(), label, ha="center", va="bottom", fontsize=9)
        for p in design.patches:
            h = heights_mm.get(p.id)
            face = "#bbbbbb" if h is None else cmap(norm(h))
            relaxed = p.diameter_mm / (2 * eta)
            ax.add_patch(Circle(p.centre_mm, relaxed, facecolor=face, edgecolor="#222222",
                                linewidth=0.6))
            ax.add_patch(Circle(p.centre_mm, p.diameter_mm / 2, fill=False, linestyle="--",
                                edgecolor="#777777", linewidth=0.5))
            ax.text(p.centre_mm[0], p.centre_mm[1], p.id, ha="center", va="center", fontsize=7)
            if p.id in flagged:
                ax.add_patch(Circle(p.centre_mm, relaxed * 1.25, fill=False,
                                    edgecolor="#c0392b", linewidth=1.8))
                ax.text(p.centre_mm[0] + relaxed * 1.3, p.centre_mm[1] + relaxed * 1.3,
                        ", ".join(dict.fromkeys(flagged[p.id])), color="#c0392b", fontsize=7)
        pts = [np.asarray(pc.outline_mm) for pc in design.pieces]
        pts += [np.array([[p.centre_mm[0] - p.diameter_mm / 2, p.centre_mm[1] - p.diameter_mm / 2],
                          [p.centre_mm[0] + p.diameter_mm / 2, p.centre_mm[1] + p.diameter_mm / 2]])
                for p in design.patches]
        allpts = np.vstack(pts)
        lo, hi = allpts.min(axis=0), allpts.max(axis=0)
        pad = 0.05 * float(max(hi - lo)) + 5.0
        ax.set_xlim(lo[0] - pad, hi[0] + pad)
        ax.set_ylim(lo[1] - pad, hi[1] + pad)
        ax.set_aspect("equal")
        ax.set_xlabel("x (mm, design frame, relaxed fabric)")
        ax.set_ylabel("y (mm)")
        ax.grid(True, linewidth=0.3, color="#dddddd")
        sm = matplotlib.cm.ScalarMappable(norm=norm, cmap=cmap)
        fig.colorbar(sm, ax=ax, shrink=0.7, label="predicted height h (mm)")
        n_err = sum(v.severity == "error" for v in violations)
        ax.set_title(f"{len(design.patches)} patch(es) on {len(design.pieces)} piece(s); "
                     f"check: {n_err} error(s), {len(violations) - n_err} warning(s)\n"
                     f"filled: footprint on the relaxed fabric (d / {eta:g}); dashed: d on the "
                     "stretched fabric; red ring: violation", fontsize=9)
        fig.tight_layout()
        return _save(fig, (fmt,))[fmt]
