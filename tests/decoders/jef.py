"""A small Janome JEF decoder written from the format description (not pyembroidery).

Little-endian header: int32 stitch-data offset, int32 flags, 14-byte date, 2 bytes, int32
colour count, int32 point count, int32 hoop code, then extents and hoop distances, the colour
table (colour count x int32) and as many int32 type words. Stitch data: two signed bytes
(dx, dy; 0.1 mm, y up) per stitch; 0x80 escapes a command followed by a move:
0x80 0x01 dx dy colour change, 0x80 0x02 dx dy jump (three zero jumps in a row: Janome trim),
0x80 0x10 end.
"""
from __future__ import annotations

import struct

from .dst import COLOR, END, JUMP, STITCH, Decoded

TRIM = "trim"
MAX_MOVE = 127


def _s8(b):
    return b - 256 if b > 127 else b


def decode(data: bytes) -> Decoded:
    offset, flags = struct.unpack_from("<ii", data, 0)
    n_colors, n_points, hoop = struct.unpack_from("<iii", data, 24)
    # the colour table: one int32 palette index per colour block, after the four hoop distances
    palette = list(struct.unpack_from(f"<{n_colors}i", data, 116))
    out = Decoded(header={"offset": offset, "colors": n_colors, "points": n_points,
                          "hoop": hoop, "date": data[8:22].decode("latin-1"),
                          "palette": palette})
    x = y = 0
    i = offset
    zero_jumps = 0
    while i + 1 < len(data):
        if data[i] != 0x80:
            x, y = x + _s8(data[i]), y + _s8(data[i + 1])
            out.records.append((STITCH, x, y))
            zero_jumps = 0
            i += 2
            continue
        ctrl = data[i + 1]
        if ctrl == 0x10:
            out.records.append((END, x, y))
            break
        dx, dy = _s8(data[i + 2]), _s8(data[i + 3])
        x, y = x + dx, y + dy
        i += 4
        if ctrl == 0x01:
            out.records.append((COLOR, x, y))
        elif ctrl == 0x02:
            out.records.append((JUMP, x, y))
            zero_jumps = zero_jumps + 1 if dx == dy == 0 else 0
            if zero_jumps == 3:
                out.records.append((TRIM, x, y))
                zero_jumps = 0
        else:
            raise ValueError(f"unknown JEF control byte 0x{ctrl:02x} at {i - 4}")
    return out
