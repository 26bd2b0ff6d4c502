"""Offscreen rendering of a scene with pyvista (VTK), to an RGB array or a PNG file.

No display and no GPU are needed: ``pyvista.OFF_SCREEN`` is set and the plotter is created
with ``off_screen=True``; VTK then renders through EGL or OSMesa (Mesa's software rasterizer on
a machine without a GPU). pyvista is imported here only, and only when a scene is rendered.
The PNG is encoded with Pillow (no metadata) and written atomically, so the same scene gives
the same bytes on the same machine and VTK build.

What makes the picture read as 3D: the camera is framed on the patches (``camera.frame_points``;
or one piece, or one patch); heights can be exaggerated by a factor K, applied to the drawn
geometry only (the colours, the colour bar and the exported mesh keep the true heights) and
stated on the image; the surface is lit by a key light from the upper left of the image, 35
degrees off the view axis, which shades the slopes of a dome facing it and facing away from it
differently from the flat fabric, plus a weak headlight so that no slope is black; the patch
ids, a scale bar and the height scale are drawn on the image (``overlay``).
"""
from __future__ import annotations

import io
import os
import re
from dataclasses import dataclass

import numpy as np

from stitchswitch.errors import InvalidInputError
from stitchswitch.files.atomic import atomic_write_bytes
from stitchswitch.preview3d import colours, overlay
from stitchswitch.preview3d.camera import Camera, check_view, fit_camera, frame_points

SIZE_RANGE = (64, 8192)
BACKGROUND = "white"
#: fraction of the width used by the scene; the rest holds the colour bar or legend
USABLE = 0.84
#: outlines are drawn this far (mm) towards the camera from the surface they lie on
LINE_LIFT_MM = 0.5
#: the height exaggeration a preview accepts
EXAGGERATE_RANGE = (1.0, 50.0)
#: the key light, fixed to the camera: its direction in camera coordinates (x right, y up, z
#: towards the viewer: from the upper left, 35 degrees off the view axis) and intensity
KEY_LIGHT = ((-0.5, 0.5, 1.0), 0.85)
HEAD_LIGHT = 0.35
#: the surface's material: ambient, diffuse and specular parts (VTK's Phong model)
MATERIAL = dict(ambient=0.12, diffuse=0.85, specular=0.25, specular_power=20.0)


@dataclass(frozen=True)
class RenderOptions:
    view: str = "iso"
    size: tuple[int, int] = (1200, 900)
    colour: str = "height"
    lighting: bool = True
    legend: bool = True
    exaggerate: float = 1.0
    piece: str | None = None       # frame this piece (default: the patches)
    patch: str | None = None       # frame this patch
    annotate: bool = True          # patch ids, scale bar, height scale

    def __post_init__(self) -> None:
        check_view(self.view)
        colours.check_colour(self.colour)
        check_exaggerate(self.exaggerate)
        if self.piece is not None and self.patch is not None:
            raise InvalidInputError("give --piece or --patch, not both")
        w, h = self.size
        lo, hi = SIZE_RANGE
        if not (lo <= w <= hi and lo <= h <= hi):
            raise InvalidInputError(f"size: {w}x{h} is outside [{lo}, {hi}] pixels per side")


def check_exaggerate(k) -> float:
    lo, hi = EXAGGERATE_RANGE
    if not (isinstance(k, (int, float)) and lo <= k <= hi):
        raise InvalidInputError(f"exaggerate: {k!r} is outside [{lo:g}, {hi:g}]")
    return float(k)


def parse_size(text: str) -> tuple[int, int]:
    """``"WxH"`` -> (W, H) pixels."""
    m = re.fullmatch(r"\s*(\d+)\s*[xX]\s*(\d+)\s*", str(text))
    if not m:
        raise InvalidInputError(f"size: {text!r} must be WIDTHxHEIGHT in pixels, e.g. 1200x900")
    size = (int(m.group(1)), int(m.group(2)))
    RenderOptions(size=size)
    return size


def _pyvista():
    import pyvista as pv
    from vtkmodules.vtkCommonCore import vtkLogger

    pv.OFF_SCREEN = True
    if not os.environ.get("DISPLAY"):
        # without a display VTK first tries X, warns "bad X server connection" and falls back
        # to EGL/OSMesa; that warning is noise here (VTK's stderr log keeps errors only)
        vtkLogger.SetStderrVerbosity(vtkLogger.VERBOSITY_ERROR)
    return pv


def polylines(pv, lines):
    """The scene's polylines (``scene.Polyline``) as one pyvista PolyData of line cells (empty
    PolyData for none): the preview's render and the studio's 3D view draw the same lines."""
    if not lines:
        return pv.PolyData()
    pts = np.vstack([ln.points for ln in lines])
    cells, start = [], 0
    for ln in lines:
        n = len(ln.points)
        cells.append(np.concatenate([[n], np.arange(start, start + n)]))
        start += n
    return pv.PolyData(pts, lines=np.concatenate(cells))


def _lights(pv, pl) -> None:
    pl.remove_all_lights()
    direction, intensity = KEY_LIGHT
    pl.add_light(pv.Light(position=direction, light_type="camera light", intensity=intensity))
    pl.add_light(pv.Light(light_type="headlight", intensity=HEAD_LIGHT))


def render_scene(scene, options: RenderOptions = RenderOptions(), status=None):
    """(image (H, W, 3) uint8, camera). ``status`` = (patch status, piece status) for the
    violations colouring (``colours.design_status``). The camera is in the drawn coordinates
    (heights times ``options.exaggerate``)."""
    pv = _pyvista()
    w, h = options.size
    usable = USABLE if options.legend else 1.0
    k = check_exaggerate(options.exaggerate)
    stretch = np.array([1.0, 1.0, k])
    # a little fabric around the patches; a piece is shown whole
    margin = 1.05 if options.piece is not None or not scene.patches else 1.2
    camera = fit_camera(frame_points(scene, options.piece, options.patch) * stretch,
                        options.view, options.size, usable, margin)
    pl = pv.Plotter(off_screen=True, window_size=(w, h))
    try:
        # pyvista's default 8x MSAA doubles the time of a software (llvmpipe) render
        pl.disable_anti_aliasing()
        pl.set_background(BACKGROUND)
        if options.lighting:
            _lights(pv, pl)
        look = dict(lighting=options.lighting, smooth_shading=options.lighting,
                    **(MATERIAL if options.lighting else {}))
        points, tris, data = scene.merged()
        if len(tris):
            mesh = pv.PolyData.from_regular_faces(points * stretch, tris)
            if options.colour == "height":
                scale = colours.height_scale(scene)
                cmap, clim = scale if scale is not None else (colours.HEIGHT_CMAP, (-1.0, 1.0))
                mesh.point_data["height (mm)"] = data["height_mm"]
                pl.add_mesh(mesh, scalars="height (mm)", cmap=cmap, clim=clim,
                            show_scalar_bar=options.legend and scale is not None,
                            scalar_bar_args=dict(title="height (mm)\n", vertical=True,
                                                 position_x=0.87, position_y=0.12,
                                                 width=0.05, height=0.7, color="black",
                                                 fmt="%.1f", title_font_size=14,
                                                 label_font_size=12), **look)
            else:
                patch_status, piece_status = status if status is not None else ({}, {})
                mesh.point_data["rgb"] = colours.point_rgb(scene, patch_status, piece_status)
                pl.add_mesh(mesh, scalars="rgb", rgb=True, **look)
                if options.legend:
                    pl.add_legend([[name, np.array(rgb) / 255.0]
                                   for name, rgb in colours.STATUS_RGB.items()],
                                  bcolor="white", border=True, loc="upper right",
                                  size=(0.14, 0.14))
        # lines lie on the surfaces; drawn LINE_LIFT_MM towards the camera so they are not
        # hidden by the surface they lie on (the exported mesh has no lines)
        towards = np.subtract(camera.position, camera.focal_point)
        lift = LINE_LIFT_MM * towards / np.linalg.norm(towards)
        for kind, colour, width in (("piece", "black", 2.0), ("patch", "#404040", 1.0)):
            group = [ln for ln in scene.lines if ln.kind == kind]
            if group:
                lines = polylines(pv, group)
                lines.points = lines.points * stretch + lift
                pl.add_mesh(lines, color=colour, line_width=width, lighting=False)
        cam = pl.camera
        cam.position, cam.focal_point, cam.up = camera.position, camera.focal_point, camera.view_up
        pl.enable_parallel_projection()
        cam.parallel_scale = camera.parallel_scale
        pl.reset_camera_clipping_range()
        image = np.array(pl.screenshot(return_img=True), dtype=np.uint8)
    finally:
        pl.close()
    if options.annotate:
        labels = [(p.id, (p.surface.centre_mm[0], p.surface.centre_mm[1],
                          max(p.height_mm, 0.0) * k)) for p in scene.patches]
        note = overlay.height_note(k) + ("" if scene.patches else "; no patches")
        image = overlay.annotate(image, camera, options.size, labels, note, usable)
    return image, camera


def png_bytes(image: np.ndarray) -> bytes:
    from PIL import Image

    buf = io.BytesIO()
    Image.fromarray(np.ascontiguousarray(image[:, :, :3])).save(buf, format="PNG")
    return buf.getvalue()


def write_png(path, image: np.ndarray) -> None:
    atomic_write_bytes(path, png_bytes(image))


def render_to_png(path, scene, options: RenderOptions = RenderOptions(), status=None) -> Camera:
    image, camera = render_scene(scene, options, status)
    write_png(path, image)
    return camera
