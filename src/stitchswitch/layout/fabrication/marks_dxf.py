"""A hooping's placement marks as DXF (garment mode), for a cutter, a plotter or the pattern CAD.

The same geometry as the 1:1 PDF template (``template``), in relaxed garment mm (the design's
frame, the pattern file's coordinates), written with ezdxf (DXF R2010, ``$INSUNITS`` 4 = mm), one
layer per kind so a plotter can draw or a CAD can hide each:

| layer | entities |
|---|---|
| ``PIECE`` | the piece outline (closed LWPOLYLINE) |
| ``HOOP_FIELD`` | the hoop's sewing field on the relaxed piece (closed LWPOLYLINE) |
| ``HOOP_FRAME`` | the outer edge of the hoop frame on the relaxed piece (closed LWPOLYLINE) |
| ``MARKS`` | the centre and the four side marks: a POINT each, and a cross of two LINEs |
| ``PATCHES`` | each patch's relaxed footprint (CIRCLE, diameter d / eta) |
| ``LABELS`` | the patch ids and the hooping's title (TEXT) |

The marks are ``layout_plot.alignment_marks`` of the hoop, turned and placed as the hooping is,
divided by eta: the same numbers as fabrication.json's ``alignment_marks_garment_mm``. The file
holds no date or random identifier (ezdxf's fixed metadata), so the same design gives the same
bytes.
"""
from __future__ import annotations

import io

import numpy as np

from stitchswitch.layout.fabrication.hoop_outline import relaxed_outline

__all__ = ["LAYERS", "marks_dxf"]

#: layer name -> AutoCAD colour index
LAYERS = {"PIECE": 8, "HOOP_FIELD": 5, "HOOP_FRAME": 9, "MARKS": 1, "PATCHES": 3, "LABELS": 7}
_MARK_NAMES = ("centre", "right", "top", "left", "bottom")


def _points(a) -> list[tuple[float, float]]:
    return [(round(float(x), 6) + 0.0, round(float(y), 6) + 0.0) for x, y in np.asarray(a)]


def marks_dxf(number: int, hooping, outline_mm, patches, eta: float) -> bytes:
    """The DXF bytes of hooping ``number``'s marks. ``outline_mm``: the relaxed piece;
    ``patches``: the hooping's ``PatchSpec`` records."""
    import ezdxf

    hoop = hooping.hoop
    fw, fh = hoop.width_mm, hoop.height_mm
    field, outer, marks = relaxed_outline(hooping, eta)
    field, outer = field[:-1], outer[:-1]           # closed by the polyline flag
    arm = 0.06 * min(fw, fh) / eta
    text_h = max(2.0, 0.02 * min(fw, fh) / eta)

    fixed = ezdxf.options.write_fixed_meta_data_for_testing
    ezdxf.options.write_fixed_meta_data_for_testing = True   # no dates, no random GUIDs
    try:
        doc = ezdxf.new("R2010", setup=False)
        doc.units = ezdxf.units.MM
        doc.header["$MEASUREMENT"] = 1
        every = np.vstack([np.asarray(outline_mm, dtype=float), outer])
        (x0, y0), (x1, y1) = _points([every.min(axis=0), every.max(axis=0)])
        doc.header["$EXTMIN"], doc.header["$EXTMAX"] = (x0, y0, 0.0), (x1, y1, 0.0)
        for name, colour in LAYERS.items():
            doc.layers.add(name, color=colour)
        msp = doc.modelspace()
        msp.add_lwpolyline(_points(outline_mm), close=True, dxfattribs={"layer": "PIECE"})
        msp.add_lwpolyline(_points(field), close=True, dxfattribs={"layer": "HOOP_FIELD"})
        msp.add_lwpolyline(_points(outer), close=True, dxfattribs={"layer": "HOOP_FRAME"})
        for (x, y), _name in zip(_points(marks), _MARK_NAMES):
            msp.add_point((x, y), dxfattribs={"layer": "MARKS"})
            msp.add_line((x - arm, y), (x + arm, y), dxfattribs={"layer": "MARKS"})
            msp.add_line((x, y - arm), (x, y + arm), dxfattribs={"layer": "MARKS"})
        for p in patches:
            (cx, cy), = _points([p.centre_mm])
            msp.add_circle((cx, cy), round(p.diameter_mm / (2 * eta), 6),
                           dxfattribs={"layer": "PATCHES"})
            msp.add_text(p.id, height=text_h, dxfattribs={"layer": "LABELS"}).set_placement(
                (cx, cy), align=ezdxf.enums.TextEntityAlignment.MIDDLE_CENTER)
        (tx, ty), = _points([outer.min(axis=0) - [0.0, 2 * text_h]])
        turned = ", turned 90" if hooping.orientation_deg == 90 else ""
        msp.add_text(f"hooping {number}: {hoop.name}{turned}; relaxed mm, 1:1",
                     height=text_h, dxfattribs={"layer": "LABELS", "insert": (tx, ty)})
        out = io.StringIO()
        doc.write(out)
    finally:
        ezdxf.options.write_fixed_meta_data_for_testing = fixed
    return out.getvalue().encode(doc.output_encoding)
