"""From one patch to machine files: tessellation, stitches, formats, machines and hoops.

* ``tessellation``: the equilateral triangle lattice and circle clipping; ``patch_geometry``:
  ``make_patch(d, p)`` and the conductive selections; ``patch_design``: ``geometry_for`` a
  design-file patch (plain, composite, outline).
* ``stitches``: ``plan_stitches`` (tatami and satin fill, ties, travel, trims) and
  ``StitchParams``; ``ordering``: the visiting order.
* ``export``: the format registry (``register_format``, ``get_format``, ``write``);
  ``stitch_preview``: SVG/PNG of a stitch plan.
* ``machines``: the machine and hoop catalogue (``catalogue``, ``load_machines``);
  ``hoop_spec``: ``Hoop``; ``hoops``: the Janome 550E hoops and ``choose_hoop``.

Below ``garment``, ``check`` and ``fabrication``; imports nothing of them.
"""
