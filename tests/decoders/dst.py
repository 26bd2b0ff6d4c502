"""A small Tajima DST decoder written from the format description (not pyembroidery).

512-byte ASCII header (LA, ST, CO, +X, -X, +Y, -Y, ... in 0.1 mm), then 3-byte records. Each
record moves by a balanced-ternary sum (0.1 mm units, y up):
byte 0: bit0 +1x, bit1 -1x, bit2 +9x, bit3 -9x, bit4 -9y, bit5 +9y, bit6 -1y, bit7 +1y
byte 1: the same with 3 and 27;  byte 2: bit2 +81x, bit3 -81x, bit4 -81y, bit5 +81y,
bit7 jump, bit6 colour change (both: 0xC3), 0xF3 (bits 0-1 set) with no move: end.
"""
from __future__ import annotations

from dataclasses import dataclass, field

STITCH, JUMP, COLOR, END = "stitch", "jump", "color", "end"
MAX_MOVE = 121  # 0.1 mm per axis


@dataclass
class Decoded:
    records: list = field(default_factory=list)   # (command, x, y) absolute, 0.1 mm, y up
    header: dict = field(default_factory=dict)

    def count(self, command):
        return sum(1 for c, _, _ in self.records if c == command)

    def extents(self, commands=(STITCH,)):
        pts = [(x, y) for c, x, y in self.records if c in commands]
        xs, ys = [p[0] for p in pts], [p[1] for p in pts]
        return min(xs), min(ys), max(xs), max(ys)

    def moves(self, commands=(STITCH,)):
        out, px, py = [], 0, 0
        for c, x, y in self.records:
            if c in commands:
                out.append((x - px, y - py))
            px, py = x, y
        return out


def _bits(b, weights):
    return sum(w for bit, w in weights if b & (1 << bit))


def decode(data: bytes) -> Decoded:
    out = Decoded()
    for line in data[:512].split(b"\r"):
        text = line.decode("latin-1")
        if len(text) >= 3 and text[2] == ":":
            out.header[text[:2]] = text[3:].strip()
    x = y = 0
    for i in range(512, len(data) - 2, 3):
        b0, b1, b2 = data[i], data[i + 1], data[i + 2]
        if b2 == 0xF3:
            out.records.append((END, x, y))
            break
        dx = (_bits(b0, [(0, 1), (1, -1), (2, 9), (3, -9)]) + _bits(b1, [(0, 3), (1, -3), (2, 27), (3, -27)])
              + _bits(b2, [(2, 81), (3, -81)]))
        dy = (_bits(b0, [(7, 1), (6, -1), (5, 9), (4, -9)]) + _bits(b1, [(7, 3), (6, -3), (5, 27), (4, -27)])
              + _bits(b2, [(5, 81), (4, -81)]))
        x, y = x + dx, y + dy
        kind = b2 & 0xC0
        out.records.append((COLOR if kind == 0xC0 else JUMP if kind == 0x80 else STITCH, x, y))
    return out
