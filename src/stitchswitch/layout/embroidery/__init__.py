"""From one patch to machine files: tessellation, stitches, formats, machines and hoops.

* ``tessellation``: the equilateral triangle lattice, clipping and ``fit_to_fill`` (the one
  pipeline from a region to stitched pieces at a fill); ``patch_geometry``:
  ``make_patch(d, p)`` and the conductive selections; ``patch_design``: ``geometry_for`` a
  design-file patch (plain, composite, outline).
* ``stitches``: ``plan_stitches`` (the routed thread over the pieces, fills, ties, travel,
  trims) and ``StitchParams``; ``sewing/``: its parts (fills, route, thread runs, the audit of
  a plan); ``ordering``: a short visiting order of points (nearest neighbour + 2-opt, used for
  the hoopings' order).
* ``export``: the format registry (``register_format``, ``get_format``, ``write``);
  ``stitch_preview``: SVG/PNG of a stitch plan; ``file_summary``: ``summarise`` an embroidery
  file from anywhere (counts, extents, fitting hoops), refusing malformed ones.
* ``machines``: the machine and hoop catalogue, the one API for both (``catalogue``,
  ``Catalogue.machine``, ``Machine.hoop`` / ``largest_hoop`` / ``choose_hoop``,
  ``DEFAULT_MACHINE``, ``load_machines``); ``hoop_spec``: ``Hoop`` and its JEF codes;
  ``jef_palette``: the Janome palette thread a JEF names for each colour block (``jef_threads``;
  ``JefThread.sheet_text`` is how the fabrication sheet names it).
* ``planar``: lengths, dot products and 2 x 2 transforms of plane vectors without BLAS, so
  that stitch paths, and the files, are the same on every processor.

Below ``garment``, ``check`` and ``fabrication``; imports nothing of them.
"""
