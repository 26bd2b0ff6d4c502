"""Patch geometry (``tessellation``, ``patch_geometry``), stitches (``stitches``, ``ordering``),
hoops, embroidery export (``export``) and previews (``preview``), see docs/embroidery.md; garment
pattern import (``dxf_import``, ``dxf_aama``, ``dxf_generic``), see docs/dxf.md. The design file,
placement and the constraint check come with issue 8; hoop grouping with issue 9."""
