"""Fabrication mode (paper, section 5, Fig. 11): from a design to a folder of machine files.

* ``fabricate``: ``fabricate(design, outdir, FabricateOptions) -> FabricationResult``.
* ``grouping/``: hoop grouping (garment and free mode).
* ``order``: the stitching order of the hoopings; ``plan``: the stitch plan of one hooping.
* ``document``: ``FabricationDoc``, what fabrication.json holds (``as_dict``), read by the sheet.
* ``sheet``: the fabrication sheet (Markdown, HTML), its plain-language parts in ``workshop``
  (legend, steps, colour stops, conflict advice) and ``hoop_reason`` (why each hooping's hoop);
  ``layout_plot``: the hooping figures; ``template``: the 1:1 printable templates;
  ``marks_dxf``: the same marks as DXF; ``hoop_outline``: where the hoop lies on the relaxed
  piece, the geometry both draw.

The top of ``layout``: it imports ``embroidery``, ``garment`` and ``check``.
"""
