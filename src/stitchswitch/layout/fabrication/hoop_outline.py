"""Where one hooping's hoop lies on the relaxed piece: the field, the frame's outer edge and the
alignment marks, in the piece's relaxed mm. The printed template and the DXF marks both draw
these, so the two always agree."""
from __future__ import annotations

from typing import NamedTuple

import numpy as np

from stitchswitch.layout.fabrication.layout_plot import alignment_marks

__all__ = ["HoopOutline", "rectangle", "relaxed_outline"]


class HoopOutline(NamedTuple):
    field_mm: np.ndarray      #: the stitch field, closed polygon (5 x 2)
    outer_mm: np.ndarray      #: the frame's outer edge, closed polygon (5 x 2)
    marks_mm: np.ndarray      #: centre, right, top, left, bottom marks (5 x 2)


def rectangle(w: float, h: float) -> np.ndarray:
    """The closed outline (first point repeated) of a ``w`` x ``h`` rectangle about the origin."""
    return np.array([[-w / 2, -h / 2], [w / 2, -h / 2], [w / 2, h / 2], [-w / 2, h / 2],
                     [-w / 2, -h / 2]])


def relaxed_outline(hooping, eta: float) -> HoopOutline:
    """``hooping``'s hoop placed and turned as the hooping is, divided by the pre-stretch
    ``eta`` (the piece is marked relaxed, stitched stretched)."""
    hoop = hooping.hoop
    fw, fh, frame = hoop.width_mm, hoop.height_mm, hoop.frame_width_mm
    return HoopOutline(hooping.to_piece(rectangle(fw, fh)) / eta,
                       hooping.to_piece(rectangle(fw + 2 * frame, fh + 2 * frame)) / eta,
                       hooping.to_piece(np.array(alignment_marks(hoop))) / eta)
