"""The 3D view's camera: the whole design in view, from the isometric direction, at the size the
page gives the view.

The render window is made before the page says how large its view is (the server-rendered view
takes the page's size when its first image is asked for), and a camera fitted to the first
size crops the design in another: fitted to 600 x 450 pixels and shown in a 510 x 766 view, the
pieces ran off both sides and covered twice the pixels of a fitted view. ``CameraFit`` fits the
camera again whenever the window's size changes, as long as the camera is where its last fit
put it; once the user has rotated or zoomed, the view stays as they left it.
"""
from __future__ import annotations


def _pose(camera) -> tuple:
    return (camera.GetPosition(), camera.GetFocalPoint(), camera.GetViewUp(),
            camera.GetViewAngle(), camera.GetParallelScale())


class CameraFit:
    """``fit()`` puts ``plotter``'s camera on the isometric view of the whole scene; after the
    first fit, a change of the render window's size fits it again unless the camera has moved
    since (``fits`` counts the fits)."""

    def __init__(self, plotter):
        self.plotter = plotter
        self.fits = 0
        self._fitted = None
        self._size = None
        plotter.ren_win.AddObserver("WindowResizeEvent", self._resized)

    def fit(self) -> None:
        self.plotter.view_isometric(render=False)
        self.plotter.reset_camera(render=False)
        self._fitted = _pose(self.plotter.camera)
        self._size = tuple(self.plotter.ren_win.GetSize())
        self.fits += 1

    @property
    def fitted(self) -> bool:
        """True once the camera has had its first fit."""
        return self._fitted is not None

    def _resized(self, window, _event) -> None:
        if (self._fitted is not None and tuple(window.GetSize()) != self._size
                and _pose(self.plotter.camera) == self._fitted):
            self.fit()
