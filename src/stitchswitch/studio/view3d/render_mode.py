"""Where the 3D view is drawn: by the browser's WebGL (trame-vtk's local view: vtk.js draws the
scene's arrays) or by VTK on the server (the remote view: the page shows the images it
sends; rotating and zooming send the pointer to the server, which renders again).

A software OpenGL (no GPU: Mesa's llvmpipe, Chromium's SwiftShader) draws the 40-patch scene
in 13 ms in VTK on the server, single-sampled, but in 66-83 ms in the browser's WebGL, whose
frame the page then composites in software (docs/studio.md, "Speed"). The studio binds to
this machine, so the browser's renderer is software when the server's is: ``auto`` renders on
the server then, and in the browser otherwise.
"""
from __future__ import annotations

import re

MODES = ("auto", "browser", "server")
#: OpenGL / WebGL renderer names of software rasterizers (the page's probe uses it too)
SOFTWARE_RENDERER = r"swiftshader|llvmpipe|softpipe|software"


def is_software(renderer: str) -> bool:
    """Whether OpenGL renderer name ``renderer`` is a software rasterizer."""
    return re.search(SOFTWARE_RENDERER, renderer, re.IGNORECASE) is not None


def server_renderer(window_class=None) -> str:
    """The name of the OpenGL renderer VTK draws with on this machine, offscreen (from a
    one-pixel window's capabilities report, of ``window_class``, default the factory's; ""
    if it has none)."""
    if window_class is None:
        import vtkmodules.vtkRenderingOpenGL2  # noqa: F401  (the factory's OpenGL windows)
        from vtkmodules.vtkRenderingCore import vtkRenderWindow as window_class

    window = window_class()
    window.SetOffScreenRendering(1)
    window.SetSize(1, 1)
    window.Render()
    report = window.ReportCapabilities() or ""
    window.Finalize()
    found = re.search(r"OpenGL renderer string:\s*(.+)", report)
    return found.group(1).strip() if found else ""


def choose(mode: str, renderer=server_renderer) -> str:
    """``browser`` or ``server`` for the requested ``mode`` (one of ``MODES``); ``auto`` looks
    at the renderer name ``renderer()`` gives, called only for ``auto``."""
    if mode not in MODES:
        raise ValueError(f"view mode {mode!r}: not one of {', '.join(MODES)}")
    if mode != "auto":
        return mode
    return "server" if is_software(renderer()) else "browser"
