"""The inspector's profile plot: the selected patch's profile z(r) from the design-space map
as a small SVG, both axes in mm at the same scale (the flat fabric at z = 0 drawn grey)."""
from __future__ import annotations

import numpy as np

WIDTH_PX, HEIGHT_PX, PAD_MM = 340, 120, 2.0


def profile_svg(r_mm, z_mm) -> str:
    """SVG of the profile (r_mm, z_mm) and its mirror image (-r, z); empty without a profile."""
    if r_mm is None or z_mm is None or len(r_mm) < 2:
        return ""
    r, z = np.asarray(r_mm, dtype=float), np.asarray(z_mm, dtype=float)
    x = np.concatenate([-r[::-1], r])
    y = np.concatenate([z[::-1], z])
    x0, x1 = x.min() - PAD_MM, x.max() + PAD_MM
    y0, y1 = min(y.min(), 0.0) - PAD_MM, max(y.max(), 0.0) + PAD_MM
    pts = " ".join(f"{a:.2f},{-b:.2f}" for a, b in zip(x, y))
    return (f'<svg xmlns="http://www.w3.org/2000/svg" width="{WIDTH_PX}" height="{HEIGHT_PX}" '
            f'viewBox="{x0:.2f} {-y1:.2f} {x1 - x0:.2f} {y1 - y0:.2f}">'
            f'<line x1="{x0:.2f}" y1="0" x2="{x1:.2f}" y2="0" stroke="#bbb" stroke-width="0.4"/>'
            f'<polyline data-profile="1" points="{pts}" fill="none" stroke="#b40426" '
            'stroke-width="0.8"/></svg>')
