"""The 3D view's camera: the whole design in view, from the isometric direction, at the size the
page gives the view.

The render window is made before the page says how large its view is (the server-rendered view
takes the page's size when its first image is asked for), and a camera fitted to the first
size crops the design in another: fitted to 600 x 450 pixels and shown in a 510 x 766 view, the
pieces ran off both sides and covered twice the pixels of a fitted view. ``CameraFit`` fits the
camera again whenever the window's size changes, as long as the camera is where its last fit
put it; once the user has rotated or zoomed, the view stays as they left it.

Drawn by the browser's WebGL, the view is never rendered on the server: only the camera is
sent to the page, whose window has another shape. There the page reports its view's size
(``page_size``), which the server's window takes so that the fit is the page's; and since the
user turns the page's camera, not the server's, the page also says when they did
(``release``).
"""
from __future__ import annotations

#: the share of the view's width or height (the tighter) that the fitted design spans
SCREEN_FILL = 0.9


def _pose(camera) -> tuple:
    return (camera.GetPosition(), camera.GetFocalPoint(), camera.GetViewUp(),
            camera.GetViewAngle(), camera.GetParallelScale())


class CameraFit:
    """``fit()`` puts ``plotter``'s camera on the isometric view of the whole scene, the scene
    spanning ``SCREEN_FILL`` of the window's tighter direction; after the first fit, a change
    of the render window's size fits it again unless the camera has moved since or was
    released to the user (``fits`` counts the fits)."""

    def __init__(self, plotter):
        self.plotter = plotter
        self.fits = 0
        self._fitted = None
        self._size = None
        self._released = False
        plotter.ren_win.AddObserver("WindowResizeEvent", self._resized)

    def fit(self) -> None:
        self.plotter.view_isometric(render=False)
        self.plotter.reset_camera(render=False)
        camera = self.plotter.camera      # pyvista's first read of it resets it: read it now
        # fitted on the screen, not by the bounding sphere: the sphere of a flat design seen
        # from the isometric direction left a corner 2 px from the edge of a 310 px wide view
        # and twice as much room on one side as the other (the aspect is the window's now,
        # not the last render's)
        self.plotter.renderer.ComputeAspect()
        self.plotter.renderer.ResetCameraScreenSpace(SCREEN_FILL)
        self.plotter.renderer.ResetCameraClippingRange()
        self._fitted = _pose(camera)
        self._size = tuple(self.plotter.ren_win.GetSize())
        self._released = False
        self.fits += 1

    @property
    def fitted(self) -> bool:
        """True once the camera has had its first fit."""
        return self._fitted is not None

    @property
    def released(self) -> bool:
        """True once ``release`` was called: the camera is the user's."""
        return self._released

    def page_size(self, width_px: float, height_px: float) -> None:
        """The page's view is ``width_px`` x ``height_px``: the window takes that size, and the
        camera its fit for it (unless the camera is the user's)."""
        self.plotter.ren_win.SetSize(max(1, round(width_px)), max(1, round(height_px)))

    def pose(self) -> dict:
        """The camera as vtk.js's ``setCamera`` takes it."""
        c = self.plotter.camera
        return {"position": list(c.GetPosition()), "focalPoint": list(c.GetFocalPoint()),
                "viewUp": list(c.GetViewUp()), "viewAngle": c.GetViewAngle(),
                "parallelScale": c.GetParallelScale(),
                "centerOfRotation": list(c.GetFocalPoint())}

    def release(self) -> None:
        """The user has moved the camera where the server's camera does not follow it (the
        browser's WebGL view): no more fits on a change of size."""
        self._released = True

    def _resized(self, window, _event) -> None:
        if (self._fitted is not None and not self._released
                and tuple(window.GetSize()) != self._size
                and _pose(self.plotter.camera) == self._fitted):
            self.fit()
