"""One embroidery hoop: its sewing field, the margin kept free of stitches and the frame ring.

Lengths are mm on the hooped (stretched) fabric. ``width_mm`` x ``height_mm`` is the sewing
field in the hoop's normal position; a placement turned by 90 degrees swaps them. The usable
area is the field shrunk by ``margin_mm`` on every side; the frame covers the ring of
``frame_width_mm`` around the field (it clamps the fabric there, and presses anything already
stitched under it). ``layout.embroidery.machines`` reads hoops from the catalogue data file and
is the API to find them (``Machine.hoop``, ``largest_hoop``, ``choose_hoop``).

``jef_code`` is the hoop code of the JEF header. The public sources disagree. libembroidery
(Embroidermodder, C) numbers them 126x110 = 0, 110x110 = 1, 50x50 = 2, 140x200 = 3,
230x200 = 4; pyembroidery 1.5 (``JefWriter.py``) numbers them 110x110 = 0, 50x50 = 1,
140x200 = 2, 126x110 = 3, 200x200 = 4. The catalogue follows pyembroidery: it is the maintained
successor of that code, its table is the one its JEF reader/writer round-trips, and
libembroidery's own hoop function is inconsistent with its table (it compares 0.1 mm extents
against mm sizes). Neither lists the 550E's SQ14b (140x140) or RE36b (200x360).

``JEF_HOOP_CODES`` is the table written (pyembroidery's). The SQ14b conflict: the catalogue
gives it code 2, which names the 140x200 field (RE20b's). It is kept on purpose: the code tells
the machine the field the design was made for, and 2 is the smallest coded field that holds
everything the SQ14b can hold, so a file never claims a field smaller than the hoop it is sewn
in; the fabrication sheet prints the code next to the hoop (``jef_code``) so the mismatch of
names is stated, not hidden. RE36b has no code (``None``): the writer then uses the smallest
coded field holding the design's real extent about the hoop centre (a design must be centred
on the field the code names), or the largest coded field (200x200) with a warning when none
holds it (``jef_code_for``). Unverified on a real 550E.
"""
from __future__ import annotations

from dataclasses import dataclass

#: JEF hoop code -> sewing field (mm), pyembroidery 1.5 ``JefWriter.py`` (libembroidery's
#: numbering differs; module docstring)
JEF_HOOP_CODES = {0: (110.0, 110.0), 1: (50.0, 50.0), 2: (140.0, 200.0), 3: (126.0, 110.0),
                  4: (200.0, 200.0)}


@dataclass(frozen=True)
class Hoop:
    name: str
    width_mm: float      # x extent of the sewing field
    height_mm: float     # y extent of the sewing field
    jef_code: int | None
    margin_mm: float = 0.0
    frame_width_mm: float = 0.0

    def fits(self, width_mm: float, height_mm: float) -> bool:
        """Whether a design of this extent fits the sewing field (margin not applied)."""
        return width_mm <= self.width_mm + 1e-9 and height_mm <= self.height_mm + 1e-9

    def field_mm(self, orientation_deg: int = 0) -> tuple[float, float]:
        """(x, y) extent of the sewing field in a placement turned by 0 or 90 degrees."""
        return ((self.height_mm, self.width_mm) if orientation_deg == 90
                else (self.width_mm, self.height_mm))

    def usable_mm(self, orientation_deg: int = 0) -> tuple[float, float]:
        """(x, y) extent of the field minus the margin on every side."""
        w, h = self.field_mm(orientation_deg)
        return w - 2.0 * self.margin_mm, h - 2.0 * self.margin_mm

    def outer_mm(self, orientation_deg: int = 0) -> tuple[float, float]:
        """(x, y) extent of the field plus the frame ring on every side."""
        w, h = self.field_mm(orientation_deg)
        return w + 2.0 * self.frame_width_mm, h + 2.0 * self.frame_width_mm

    @property
    def area_mm2(self) -> float:
        return self.width_mm * self.height_mm

    @property
    def orientations(self) -> tuple[int, ...]:
        """0 and 90 degrees; a square hoop has only 0 (turning it changes nothing)."""
        return (0,) if abs(self.width_mm - self.height_mm) < 1e-9 else (0, 90)

    def __str__(self) -> str:
        return f"{self.name} {self.width_mm:g} x {self.height_mm:g} mm"


def jef_code_for(hoop: Hoop, bounds_mm: tuple[float, float, float, float]) -> tuple[int, bool]:
    """(code, published): the hoop's own JEF code, or for a hoop without one the smallest
    coded field (by area) holding the design ``bounds_mm`` (xmin, ymin, xmax, ymax about the
    hoop centre) centred, else the largest coded field."""
    if hoop.jef_code is not None:
        return hoop.jef_code, True
    x0, y0, x1, y1 = bounds_mm
    need_w, need_h = 2 * max(abs(x0), abs(x1)), 2 * max(abs(y0), abs(y1))
    holding = [(w * h, code) for code, (w, h) in JEF_HOOP_CODES.items()
               if need_w <= w + 1e-9 and need_h <= h + 1e-9]
    if holding:
        return min(holding)[1], False
    return max((w * h, code) for code, (w, h) in JEF_HOOP_CODES.items())[1], False
