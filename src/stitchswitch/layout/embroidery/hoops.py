"""Embroidery hoops of the Janome MemoryCraft 550E and their JEF header codes.

JEF hoop codes: the public sources disagree. libembroidery (Embroidermodder, C) numbers them
126x110 = 0, 110x110 = 1, 50x50 = 2, 140x200 = 3, 230x200 = 4; pyembroidery 1.5
(``JefWriter.py``) numbers them 110x110 = 0, 50x50 = 1, 140x200 = 2, 126x110 = 3, 200x200 = 4.
We follow pyembroidery: it is the maintained successor of that code, its table is the one its
JEF reader/writer round-trips, and libembroidery's own hoop function is inconsistent with its
table (it compares 0.1 mm extents against mm sizes). Neither lists the 550E's SQ14b (140x140) or
RE36b (200x360): SQ14b gets code 2 (the 140x200 hoop, the smallest coded hoop holding its whole
field) and RE36b keeps ``None``, meaning "no published code": the writer then keeps pyembroidery's
size-based code and logs a warning (docs/embroidery.md).

The hoops, with their margins and frame widths, now come from the machine catalogue
(``stitchswitch/data/machines.json``, read by ``layout.embroidery.machines``; docs/fabrication.md);
``Hoop`` lives in ``layout.embroidery.hoop_spec`` and is re-exported here.
"""
from __future__ import annotations

from stitchswitch.errors import InvalidInputError
from stitchswitch.layout.embroidery.hoop_spec import Hoop
from stitchswitch.layout.embroidery.machines import builtin_catalogue

__all__ = ["Hoop", "JANOME_550E_HOOPS", "choose_hoop", "hoops_fitting"]

JANOME_550E_HOOPS: tuple[Hoop, ...] = builtin_catalogue().machine("janome-550e").hoops


def hoops_fitting(width_mm: float, height_mm: float, hoops=JANOME_550E_HOOPS) -> list[Hoop]:
    return [h for h in hoops if h.fits(width_mm, height_mm)]


def choose_hoop(width_mm: float, height_mm: float, name: str | None = None,
                hoops=JANOME_550E_HOOPS) -> Hoop:
    """The named hoop (checked), or the smallest (by area) hoop the design fits."""
    if name is not None:
        match = [h for h in hoops if h.name.lower() == name.lower()]
        if not match:
            raise InvalidInputError(f"unknown hoop {name!r}; the hoops are "
                                    + ", ".join(h.name for h in hoops))
        if not match[0].fits(width_mm, height_mm):
            raise InvalidInputError(f"a {width_mm:.1f} x {height_mm:.1f} mm design does not fit "
                                    f"the hoop {match[0]}")
        return match[0]
    fit = hoops_fitting(width_mm, height_mm, hoops)
    if not fit:
        largest = max(hoops, key=lambda h: h.width_mm * h.height_mm)
        raise InvalidInputError(f"a {width_mm:.1f} x {height_mm:.1f} mm design fits no hoop; "
                                f"the largest is {largest}")
    return min(fit, key=lambda h: h.width_mm * h.height_mm)
