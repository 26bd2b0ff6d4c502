"""Finite-element shell reference (scikit-fem), issue 5 -- IN PROGRESS.

``density``: the continuum energy density (the reduced model's continuum limit, plus switches
for hoop bending and Poisson coupling) with exact first and second derivatives. ``shell``: the
axisymmetric shell on a MeshLine with cubic Hermite elements, assembled with scikit-fem forms and
solved by Newton from the reduced equilibrium. Not yet done: the convergence study (fine meshes
do not converge cleanly, see the issue note), ``stitchswitch fem-check``, the switching-force
path, mesh export and the benchmark.
"""
