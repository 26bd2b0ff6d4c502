"""Patch geometry (``tessellation``, ``patch_geometry``), stitches (``stitches``, ``ordering``),
hoops, embroidery export (``export``) and previews (``preview``), see docs/embroidery.md; garment
pattern import (``dxf_import``, ``dxf_aama``, ``dxf_generic``), see docs/dxf.md. The design file,
placement and the constraint check come with issue 8. Fabrication mode (issue 9,
docs/fabrication.md): the machine catalogue (``machines``), hoop grouping (``hoop_grouping``:
``hoop_garment``, ``hoop_free``), stitching order (``hoop_order``), per-hoop plans and the
output folder (``fabricate``)."""
