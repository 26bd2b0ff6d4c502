"""Finite-element shell reference (scikit-fem) that checks the reduced model (docs/fem-reference.md).

``density``: the continuum energy density (the reduced model's continuum limit, plus switches
for hoop bending and Poisson coupling) with exact first and second derivatives. ``shell``: the
axisymmetric shell on a MeshLine with cubic Hermite elements, assembled with scikit-fem forms,
solved by Newton. ``continuation``: the prestretch continuation from the flat sheet (the default
start; the reduced equilibrium is the other). ``check``: ``stitchswitch fem-check``.
``switching``: the switching force by displacement control (``stitchswitch switch-force``).
"""
