"""Annotations drawn on a rendered preview image: patch ids, a scale bar and the height scale.

They are drawn with Pillow after rendering, at the pixels the camera maps the world points to
(``camera.world_to_pixel``), so they never depend on VTK's text rendering and are identical on
every run. The font is the DejaVu Sans that matplotlib ships.

Scale bar. Every view is a parallel projection, so one pixel is ``2 parallel_scale / height``
mm everywhere in the image plane. The image's horizontal is a direction of the garment plane in
every view (x in ``top`` and ``side``; (1, 1, 0) / sqrt 2 in ``iso``), so a horizontal bar has
its true length on the fabric; vertical lengths in ``iso`` are foreshortened and heights are
multiplied by the exaggeration, which the image states.
"""
from __future__ import annotations

import math

import numpy as np

from stitchswitch.preview3d.camera import Camera, world_to_pixel

#: the scale bar is the longest 1, 2 or 5 x 10^k mm not longer than this fraction of the width
SCALE_BAR_FRACTION = 0.2


def nice_length_mm(max_mm: float) -> float:
    """The longest 1, 2 or 5 x 10^k mm that is at most ``max_mm``."""
    if not max_mm > 0:
        raise ValueError(f"max_mm must be > 0, got {max_mm!r}")
    k = math.floor(math.log10(max_mm))
    for m in (5, 2, 1):
        if m * 10.0 ** k <= max_mm * (1 + 1e-12):
            return m * 10.0 ** k
    return 10.0 ** k


def mm_per_pixel(camera: Camera, size: tuple[int, int]) -> float:
    return 2.0 * camera.parallel_scale / size[1]


def height_note(exaggerate: float) -> str:
    """What the image says about its vertical scale."""
    if exaggerate == 1.0:
        return "heights to scale (x 1)"
    return f"heights exaggerated x {exaggerate:g}"


def _font(px: int):
    from matplotlib import font_manager
    from PIL import ImageFont

    path = font_manager.findfont(font_manager.FontProperties(family="DejaVu Sans"))
    return ImageFont.truetype(path, px)


def annotate(image: np.ndarray, camera: Camera, size: tuple[int, int], labels, note: str,
             usable: float = 1.0) -> np.ndarray:
    """``image`` (H, W, 3) with the ``labels`` ((text, (x, y, z)) in the world coordinates
    drawn, already exaggerated) above their points (those in the ``usable`` left part of the
    width), a scale bar at the bottom left and ``note`` at the top left, both on white boxes."""
    from PIL import Image, ImageDraw

    w, h = size
    img = Image.fromarray(np.ascontiguousarray(image[:, :, :3]))
    draw = ImageDraw.Draw(img)
    px = max(10, round(h / 48))
    font, small = _font(px), _font(max(9, round(px * 0.85)))
    for text, xyz in labels:
        col, row = world_to_pixel(camera, size, [xyz])[0]
        if 0 <= col < usable * w and 0 <= row < h:      # not over the colour bar
            draw.text((col, row - px * 0.6), str(text), font=font, fill=(0, 0, 0), anchor="md",
                      stroke_width=max(1, px // 6), stroke_fill=(255, 255, 255))
    per_px = mm_per_pixel(camera, size)
    length = nice_length_mm(SCALE_BAR_FRACTION * usable * w * per_px)
    bar = length / per_px
    x0, y0 = round(0.03 * w), round(h - 0.05 * h)
    x1, tick = round(x0 + bar), max(3, px // 3)
    width = max(2, px // 5)
    pad = max(3, px // 3)
    draw.rectangle([x0 - pad, y0 - tick - 2 - px - pad, x1 + pad, y0 + tick + pad],
                   fill=(255, 255, 255))
    draw.line([(x0, y0), (x1, y0)], fill=(0, 0, 0), width=width)
    for x in (x0, x1):
        draw.line([(x, y0 - tick), (x, y0 + tick)], fill=(0, 0, 0), width=max(1, width // 2))
    draw.text(((x0 + x1) / 2, y0 - tick - 2), f"{length:g} mm", font=small, fill=(0, 0, 0),
              anchor="md")
    left, top, right, bottom = draw.textbbox((x0, round(0.03 * h)), note, font=small, anchor="la")
    draw.rectangle([left - pad, top - pad, right + pad, bottom + pad], fill=(255, 255, 255))
    draw.text((x0, round(0.03 * h)), note, font=small, fill=(0, 0, 0), anchor="la")
    return np.asarray(img, dtype=np.uint8)
