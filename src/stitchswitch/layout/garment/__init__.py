"""The garment side of a design: pieces, patches placed on them, and the design file.

* ``design``: ``Design``, ``PieceSpec``, ``PatchSpec`` and the other frozen records of the file.
* ``design_io``: ``load_design`` / ``save_design`` / ``validate_design`` (version 1,
  docs/design-file.md; the machine and hoop checked against ``layout.embroidery.machines``).
* ``placement``: ``place_at``, ``place_grid``, ``place_along``; ``piece_select``: pieces of an
  imported pattern; ``patterns``: the paper's two applications.
* ``dxf/``: garment pattern import (``import_dxf``).

Imports ``layout.embroidery`` (patch geometry) and ``reduced.model``.
"""
