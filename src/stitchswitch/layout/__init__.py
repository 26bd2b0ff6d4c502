"""Patch geometry, stitches, DXF import, placement, hoops, export. Not implemented yet: see issues 7-9."""
