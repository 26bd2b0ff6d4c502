"""The constraint check of a design (paper, section 5), docs/design-file.md.

* ``constraints``: ``check_design(design, limits) -> list[Violation]``, ``CheckLimits``.
* ``violation``: ``Violation`` (rule, severity, patches, pieces, value, limit, message, hint).
* ``small_pieces``: ``small_piece_warnings(design, limits) -> list[SmallPieces]``: patches
  with stitched pieces under 1 mm^2, a warning (not a violation) as fabricate's sheet gives.
* ``report``: ``check_report(design, limits) -> CheckReport``: both of the above at the same
  limits, with the JSON ``stitchswitch check --json`` and the demo's check.json carry.
* ``design_point``: ``admissible(limits, hoops)``, ``for_machine(...)``: the rules an unplaced
  design (d, p) breaks wherever it goes, for inverse design.
* ``rules/``: one module per rule, each ``check(design, limits, eta) -> list[Violation]``;
  ``rules/hoopable`` also holds the hoop-placement search fabrication's grouping uses.

Imports ``layout.garment`` and ``layout.embroidery``; ``fabrication`` and the apps sit above it.
"""
