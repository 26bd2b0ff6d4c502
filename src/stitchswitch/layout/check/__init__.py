"""The constraint check of a design (paper, section 5), docs/design-file.md.

* ``constraints``: ``check_design(design, limits) -> list[Violation]``, ``CheckLimits``.
* ``violation``: ``Violation`` (rule, severity, patches, pieces, value, limit, message, hint).
* ``design_point``: ``admissible(limits, hoops)``, ``for_machine(...)``: the rules an unplaced
  design (d, p) breaks wherever it goes, for inverse design.
* ``rules/``: one module per rule, each ``check(design, limits, eta) -> list[Violation]``;
  ``rules/hoopable`` also holds the hoop-placement search fabrication's grouping uses.

Imports ``layout.garment`` and ``layout.embroidery``; ``fabrication`` and the apps sit above it.
"""
