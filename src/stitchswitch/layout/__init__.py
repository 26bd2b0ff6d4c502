"""From a design to fabric: garment patterns, patch placement, the constraint check, stitches,
machine files and fabrication mode.

Layers, bottom to top (each imports only those below it):

* ``embroidery/``: one patch's geometry and stitches, the format registry, machines and hoops
  (docs/embroidery.md).
* ``garment/``: the design file, placement and pattern import (``garment/dxf/``,
  docs/design-file.md, docs/dxf.md).
* ``check/``: the constraint check and its rules.
* ``fabrication/``: hoop grouping (``fabrication/grouping/``), stitching order, per-hoop files and
  the fabrication sheet (docs/fabrication.md).
"""
