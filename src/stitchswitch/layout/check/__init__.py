"""The constraint check of a design (paper, section 5), docs/design-file.md.

* ``constraints``: ``check_design(design, limits) -> list[Violation]``, ``CheckLimits``.
* ``violation``: ``Violation``.
* ``rules/``: one module per rule, each ``check(design, limits, eta) -> list[Violation]``.

Imports ``layout.garment`` and ``layout.embroidery``; ``fabrication`` and the apps sit above it.
"""
