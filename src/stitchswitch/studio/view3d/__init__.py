"""The studio's 3D view: the design's scene as pyvista actors, where it is drawn, and how each
edit reaches the page.

* ``scene3d``: ``Scene3D``, the view's scene (``preview3d.scene.SceneBuilder``, the one scene
  builder of ``stitchswitch preview``, rebuilt incrementally), and ``PlotterSync``, its
  pyvista actors.
* ``render_mode``: ``choose``, where the view is drawn: the browser's WebGL (trame-vtk's local
  view), or VTK on the server (its remote view) when this machine's OpenGL is software.
* ``view_channel``: ``ViewChannel``, the local view's changes sent to the page (one scene in
  flight, the newest wins; the full scene state once edits pause).
* ``image_channel``: ``ImageChannel``, the remote view's image of each edit, pushed as soon
  as the encoder has it.
* ``camera_fit``: ``CameraFit``, the whole design in view at the size the page gives the view,
  until the user moves the camera.
"""
