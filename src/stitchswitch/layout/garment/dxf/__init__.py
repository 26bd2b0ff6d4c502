"""Garment pattern pieces from DXF files (docs/dxf.md).

* ``reader``: ``import_dxf(path) -> ImportedPieces``, outlines in mm; picks the reader below.
* ``aama``: AAMA/ASTM files (Gerber AccuMark, CLO): one BLOCK per piece and size.
* ``generic``: plain DXF entities flattened to polylines and chained into closed outlines.
"""
