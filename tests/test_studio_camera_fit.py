"""The 3D view's camera (``CameraFit``), offscreen: fitted to the window's size, fitted again
when the page gives the view another size, and left alone once the user has moved it."""
import numpy as np
import pytest

from stitchswitch.studio.view3d.camera_fit import CameraFit

pv = pytest.importorskip("pyvista")


def plotter(size=(600, 450)):
    pv.OFF_SCREEN = True
    pl = pv.Plotter(off_screen=True, window_size=size)
    pl.set_background("white")
    pl.add_mesh(pv.Plane(i_size=400, j_size=300), color="black")
    return pl


def extent(pl):
    """(share of the pixels the plane covers, its columns' range, the image's width), rendered
    as the studio's server does: the render window itself, not pyvista's screenshot."""
    from vtkmodules.util.numpy_support import vtk_to_numpy
    from vtkmodules.vtkRenderingCore import vtkWindowToImageFilter

    pl.ren_win.Render()
    grab = vtkWindowToImageFilter()
    grab.SetInput(pl.ren_win)
    grab.Update()
    w, h = pl.ren_win.GetSize()
    img = vtk_to_numpy(grab.GetOutput().GetPointData().GetScalars()).reshape(h, w, -1)[..., :3]
    dark = (img < 128).all(axis=2)
    cols = np.where(dark.any(axis=0))[0]
    return dark.mean(), (int(cols.min()), int(cols.max())), img.shape[1]


def test_the_camera_is_fitted_again_at_the_size_the_page_gives():
    pl = plotter()
    fit = CameraFit(pl)
    assert not fit.fitted
    fit.fit()
    pl.ren_win.Render()
    pl.ren_win.SetSize(510, 766)
    assert fit.fits == 2
    share, (c0, c1), width = extent(pl)
    assert c0 > 0 and c1 < width - 1                # the whole plane in view, not cropped
    fresh = plotter((510, 766))
    CameraFit(fresh).fit()
    assert share == pytest.approx(extent(fresh)[0], rel=0.02)


def test_without_the_refit_the_view_is_cropped():
    """What the refit is for: a camera fitted at 600 x 450 crops the plane in a tall view."""
    pl = plotter()
    pl.view_isometric(render=False)
    pl.reset_camera(render=False)
    pl.ren_win.Render()
    pl.ren_win.SetSize(510, 766)
    _, (c0, c1), width = extent(pl)
    assert c0 == 0 and c1 == width - 1


def test_a_camera_the_user_moved_stays_where_they_left_it():
    pl = plotter()
    fit = CameraFit(pl)
    fit.fit()
    pl.camera.azimuth = 30.0
    moved = pl.camera.position
    pl.ren_win.SetSize(510, 766)
    assert fit.fits == 1 and pl.camera.position == moved


def test_the_same_size_again_fits_nothing():
    pl = plotter()
    fit = CameraFit(pl)
    fit.fit()
    pl.ren_win.SetSize(600, 450)
    assert fit.fits == 1


def test_the_page_size_of_a_webgl_view_fits_the_camera_to_it():
    """Drawn by the browser, the view's window on the server is never shown: the page's size
    of it reaches the server (``page_size``), and the pose sent back (``pose``) is the fit for
    that size, the one a server window of that size would have."""
    pl = plotter()
    fit = CameraFit(pl)
    fit.fit()
    fit.page_size(510.4, 766.0)
    assert tuple(pl.ren_win.GetSize()) == (510, 766) and fit.fits == 2
    fresh = plotter((510, 766))
    CameraFit(fresh).fit()
    pose = fit.pose()
    assert pose["position"] == pytest.approx(list(fresh.camera.position))
    assert pose["focalPoint"] == pytest.approx(list(fresh.camera.focal_point))
    assert pose["viewUp"] == pytest.approx(list(fresh.camera.up))
    assert pose["viewAngle"] == pytest.approx(fresh.camera.view_angle)
    assert pose["centerOfRotation"] == pose["focalPoint"]


def test_a_camera_released_to_the_user_is_not_fitted_again_until_fit():
    """The page's camera turned by the user (the server's does not follow it): a change of the
    page's size leaves it; an explicit fit takes it back."""
    pl = plotter()
    fit = CameraFit(pl)
    fit.fit()
    fit.release()
    assert fit.released
    fit.page_size(510, 766)
    assert fit.fits == 1
    fit.fit()
    assert not fit.released and fit.fits == 2
    fit.page_size(600, 450)
    assert fit.fits == 3


@pytest.mark.parametrize("size", [(600, 450), (510, 766), (310, 766)])
def test_the_fit_leaves_room_on_either_side_and_fills_the_view(size):
    """Fitted on the screen, not by the bounding sphere (which left the plane 2 px from the edge
    of a 310 px wide view, and 3 px of a 510 px one): room on both sides, and the plane spans
    most of the view's width."""
    pl = plotter(size)
    CameraFit(pl).fit()
    _, (c0, c1), width = extent(pl)
    assert min(c0, width - 1 - c1) >= 0.03 * width
    assert c1 - c0 >= 0.85 * width
