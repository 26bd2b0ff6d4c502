"""Solvers of the reduced model: from a ``Patch`` and a ``Material`` to a certified equilibrium.

* ``solve``: ``solve(patch, material) -> Solution``, the public entry point (also
  ``stitchswitch.solve``).
* ``newton``: the certified projected Newton method; ``newton_loop``: its iterations, compiled
  (``fused``: the default energy as one compiled function; ``step``: active set, reduced
  variables and shifted Newton direction; ``retraction``: the polar step; ``banded``: banded
  L D L^T factor, restriction, lowest mode; ``bordered``: the Newton system with the long merged
  groups' heights as a dense border); ``constraints``: the bound constraints, projection and KKT
  residual.
* ``continuation``: starting states (the released state, the release continuation).
* ``adam``: the paper's projected Adam, kept as a baseline.

Imports ``reduced.model`` only.
"""
