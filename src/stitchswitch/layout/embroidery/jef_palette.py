"""The JEF thread palette: which Janome thread a JEF file names for each colour block.

A JEF file stores no colour values, only an index per colour block into the Janome thread
palette; the machine shows that palette entry's name and Janome thread number, not the colour
the design asked for. The palette is pyembroidery's (1.5.1, ``EmbThreadJef.get_thread_set``:
78 entries, index 0 unused), which is the same table, in the same order, with the same names and
numbers, as libembroidery's ``jefThreads`` (Embroidermodder). Its writer picks, for each block,
the entry nearest the thread's colour (pyembroidery's red-mean colour distance,
``EmbThread.find_nearest_color_index``); when two consecutive blocks of different threads land
on the same entry, the second takes the next nearest, so the machine shows a different thread at
every colour change (pyembroidery compares threads by colour and name; in our plans two
consecutive blocks are always different threads). ``jef_threads`` applies the same rule through
the same functions, so the
fabrication sheet can name what the machine will display; the tests decode the written JEF's
colour table and compare it with this. Whether a real 550E shows exactly these names has not
been checked on the machine.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Sequence

__all__ = ["JefThread", "is_jef", "palette", "jef_threads", "machine_thread_text"]


@dataclass(frozen=True)
class JefThread:
    """One palette entry: the index the JEF file stores, the Janome thread number and name the
    machine displays, and the entry's colour."""

    index: int
    number: str
    name: str
    colour: str          # "#rrggbb"

    def text(self) -> str:
        return f"{self.name} (Janome {self.number}, JEF colour {self.index})"

    def sheet_text(self, design_colour: str) -> str:
        """How the fabrication sheet names the thread of a block the design sews in
        ``design_colour``."""
        return (f"{self.name}, Janome {self.number} (JEF colour {self.index}, design colour "
                f"{design_colour})")

    def as_dict(self) -> dict:
        """The entry as fabrication.json's ``jef_thread`` records it."""
        return {"index": self.index, "number": self.number, "name": self.name,
                "colour": self.colour}


def is_jef(embroidery_file) -> bool:
    """Whether the machine file is a JEF (its colours are then palette threads)."""
    return str(embroidery_file).lower().endswith(".jef")


def _rgb_int(colour) -> int:
    if isinstance(colour, str):
        h = colour.strip().lstrip("#")
        if len(h) != 6:
            raise ValueError(f"colour {colour!r} is not #rrggbb")
        return int(h, 16)
    r, g, b = (int(v) for v in colour)
    return (r << 16) | (g << 8) | b


def _table():
    from pyembroidery.EmbThreadJef import get_thread_set
    return get_thread_set()


def palette() -> tuple[JefThread, ...]:
    """Every entry of the palette the JEF writer uses, by index (index 0 is unused)."""
    return tuple(JefThread(i, t.catalog_number, t.description, t.hex_color())
                 for i, t in enumerate(_table()) if t is not None)


def jef_threads(colours: Sequence) -> tuple[JefThread, ...]:
    """The palette entry the JEF writer stores for each colour block, in file order;
    ``colours``: each block's thread colour ("#rrggbb" or (r, g, b)), consecutive blocks being
    different threads (as a colour change always separates two)."""
    from pyembroidery.EmbThread import find_nearest_color_index

    table = _table()
    out, last_index = [], None
    for c in colours:
        value = _rgb_int(c)
        k = find_nearest_color_index(value, table)
        if k == last_index:
            kept, table[k] = table[k], None          # the writer's "no repeat" rule
            k = find_nearest_color_index(value, table)
            table[last_index] = kept
        t = table[k]
        out.append(JefThread(k, t.catalog_number, t.description, t.hex_color()))
        last_index = k
    return tuple(out)


def machine_thread_text(colours: Sequence) -> list[str]:
    """For each block: "<name> (Janome <number>, JEF colour <index>)"."""
    return [t.text() for t in jef_threads(colours)]
