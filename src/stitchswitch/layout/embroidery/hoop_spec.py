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
against mm sizes). Neither lists the 550E's SQ14b (140x140) or RE36b (200x360): SQ14b gets code 2
(the 140x200 hoop, the smallest coded hoop holding its whole field) and RE36b keeps ``None``,
meaning "no published code": the writer then keeps pyembroidery's size-based code and logs a
warning (docs/embroidery.md).
"""
from __future__ import annotations

from dataclasses import dataclass


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
