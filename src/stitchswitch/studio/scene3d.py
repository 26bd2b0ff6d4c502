"""The 3D view's geometry: the design's scene built by ``preview3d.scene.build_scene`` (the one
scene builder of ``stitchswitch preview``) as pyvista meshes, updated in place so the browser
view (trame's VTK local view) only receives the new arrays.
"""
from __future__ import annotations

from stitchswitch.preview3d import colours
from stitchswitch.preview3d.render import polylines
from stitchswitch.preview3d.scene import build_scene
from stitchswitch.preview3d.spec import spec_from_design


class Scene3D:
    """The surface mesh (point data ``height (mm)``) and the outline lines of a design."""

    def __init__(self):
        import pyvista as pv

        self._pv = pv
        self.surface = pv.PolyData()
        self.lines = pv.PolyData()
        self.clim = (-1.0, 1.0)

    def update(self, design) -> None:
        scene = build_scene(spec_from_design(design))
        points, tris, data = scene.merged()
        pv = self._pv
        new = pv.PolyData.from_regular_faces(points, tris) if len(tris) else pv.PolyData()
        if len(tris):
            new.point_data["height (mm)"] = data["height_mm"]
        self.surface.copy_from(new)
        self.lines.copy_from(polylines(pv, list(scene.lines)))
        self.clim = colours.height_clim(scene)
