"""Pattern helpers for the paper's two applications (section 6).

* ``button_array``: the programmable garment interface (6.2), a forearm garment with an array of
  patches used as tactile buttons; the paper stitches them with conductive thread in the bobbin
  and senses them with conductive pads underneath.
* ``pocket_patch``: the tennis-skirt pocket (6.1), one large patch whose stable cavity holds a
  tennis ball; the paper reports a pocket height of 17.5 mm (17.8 mm after play and a wash).

The paper gives neither the buttons' nor the pocket's d, p or spacing, so these helpers take
them as arguments; ``stitchswitch inverse --height 17.5`` suggests (d, p) for a target height.
"""
from __future__ import annotations

from stitchswitch.layout.garment.design import Design
from stitchswitch.layout.garment.placement import add_patches, grid_centres, piece_centroid

__all__ = ["button_array", "pocket_patch", "button_pitch_mm"]


def button_pitch_mm(diameter_mm: float, eta: float, spacing_mm: float) -> float:
    """The centre-to-centre pitch (garment mm) leaving ``spacing_mm`` of relaxed fabric between
    the flat footprints (diameter d / eta) of neighbouring buttons."""
    return diameter_mm / eta + spacing_mm


def button_array(design: Design, piece: str, rows: int, cols: int, diameter_mm: float,
                 fill: float, *, pitch_mm=None, spacing_mm: float = 10.0, centre_mm=None,
                 conductive: str | None = None, id_prefix: str = "button", **kwargs) -> Design:
    """A rows x cols array of tactile buttons on ``piece``, centred on ``centre_mm`` (default
    the piece's centroid). ``pitch_mm`` (one number or (x, y)) defaults to the footprint
    diameter d / eta plus ``spacing_mm``. ``conductive`` is a selection (e.g. ``ring:0``) of
    triangles sewn in conductive thread; None leaves the choice to the bobbin, as in the paper."""
    if pitch_mm is None:
        pitch_mm = button_pitch_mm(diameter_mm, design.material_object().eta, spacing_mm)
    if centre_mm is None:
        centre_mm = piece_centroid(design.piece(piece).outline_mm)
    centres = grid_centres(rows, cols, pitch_mm, centre_mm)
    return add_patches(design, piece, centres, diameter_mm, fill, id_prefix=id_prefix,
                       conductive=conductive, **kwargs)


def pocket_patch(design: Design, piece: str, diameter_mm: float, fill: float, *,
                 centre_mm=None, id_prefix: str = "pocket", state: str = "up",
                 **kwargs) -> Design:
    """One large pocket patch on ``piece`` at ``centre_mm`` (default the piece's centroid),
    popped outward (``state="up"``) to form the cavity."""
    if centre_mm is None:
        centre_mm = piece_centroid(design.piece(piece).outline_mm)
    return add_patches(design, piece, [centre_mm], diameter_mm, fill, id_prefix=id_prefix,
                       state=state, **kwargs)
