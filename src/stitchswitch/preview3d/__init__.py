"""3D preview of a design: patch surfaces on the garment pieces, rendered offscreen.

* ``spec``: what is previewed: pieces, patches (centre, d, fill, state) and the material; built
  from a design file's ``Design`` by ``spec_from_design`` or directly.
* ``profiles``: the equilibrium profile of every patch, from the design-space map (or a direct
  solve outside the map's domain).
* ``surfaces``: one patch's profile blended into the flat fabric, revolved and placed on the
  garment, popped up or down.
* ``fabric``: the flat pieces with the patch footprints cut out, triangulated.
* ``scene``: all of it, plus the outlines as lines; merged into one mesh for export;
  ``SceneBuilder`` rebuilds only the parts an edit changed (the studio's 3D view).
* ``camera``, ``render``: offscreen pyvista rendering to PNG (pyvista is imported only there),
  framed on the patches (or a piece, or a patch), lit to show relief, heights optionally
  exaggerated.
* ``overlay``: patch ids, a scale bar and the height scale drawn on the rendered image.
* ``colours``: height colour map (0 to the largest height when no patch is down), or which
  patches violate the design constraints.
* ``single``: cross-section figures with matplotlib: one patch's profile (keypoints,
  dimensions), and the section view through a patch of a design's scene.
* ``mesh_io``: mesh export through meshio (VTU, PLY, OBJ), atomic.

Coordinates and the blend are documented in ``surfaces`` and in docs/preview.md.
"""
