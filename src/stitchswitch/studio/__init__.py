"""The studio: the interactive design tool in the browser (paper, section 5: live preview,
inverse design, constraint panel, Fabrication Mode with hoop grouping and export).

The app state and its actions are plain Python, usable and tested without a browser; the web
page (``app``, trame) only binds widgets to them.

* ``state``: ``StudioState``, the design under edit, the selection (one patch or several), add /
  move / edit / remove patches, another size of the pattern, undo / redo.
* ``readout``: ``readout(dmap, d, fill)``, the live keypoints, profile and force of a design
  from the design-space map; ``heights_mm`` of every patch; ``profile_svg``, the selected
  patch's profile for the inspector.
* ``live_check``: ``run_check`` and the incremental ``LiveCheck``, the library constraint check,
  as panel rows.
* ``inverse_panel``: ``candidates(target, dmap, state)`` and ``apply``.
* ``persist``: ``Document``, saving (byte-identical when unchanged) and the autosave sidecar.
* ``fabrication``: ``hoopings`` (grouping and order), ``hooping_plan`` (one hooping's stitches)
  and ``export`` (``fabricate``).
* ``stitch_preview``: ``plan_svg``, a hooping's stitch plan as SVG, and its ``counts``.
* ``canvas``: the 2D canvas as SVG markup (rulers, the edge rule while dragging), zoom and pan,
  and the mapping of a click back to garment mm.
* ``view3d``: the 3D view: its scene and pyvista actors, where it is drawn (the browser's
  WebGL or VTK on the server) and how each edit reaches the page.
* ``session``: ``Session``, everything the page shows, recomputed after each action.
* ``check_timer``: ``CheckTimer``, when the check runs after an edit (at once; after a slider
  step whose 3D view is rendered on the server, once the page draws the step's image).
* ``heap``: ``freeze_long_lived``, the server's long-lived objects kept out of the garbage
  collector's full collections (each held the event loop about 80 ms).
* ``app``: the trame page and ``serve(session, port, host, open_browser, view_mode)``.

trame, trame-vuetify and trame-vtk are the optional extra ``stitchswitch[studio]``; only
``app`` imports them (and ``view3d.image_channel``, when the page runs).
"""
