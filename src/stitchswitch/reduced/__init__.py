"""The reduced 1D energy model of the paper (section 4), its solvers and the design space.

Layers, bottom to top (each imports only those below it):

* ``model/``: parameters, discretization, the energy terms, assembly, keypoints, material files.
* ``solvers/``: ``solve(patch, material) -> Solution``, certified projected Newton, Adam.
* ``calibration/`` and ``design_space/``: fitting the material to data; the precomputed map,
  inverse design and the force model.

The public entry points are re-exported at the top: ``stitchswitch.solve``, ``Patch``,
``Material``, ``DEFAULT_MATERIAL``.
"""
