"""The reduced 1D energy model of the paper (section 4) and its solvers.

Modules: ``params`` (Material, Patch), ``discretization`` (the adaptive grid), ``terms/``
(one energy term per module, each with gradient and Hessian), ``assembly`` (sums the terms
into a gradient and a banded Hessian), ``newton`` (the certified projected Newton solver),
``adam`` (the paper's projected Adam baseline), ``solve`` (the public entry point) and
``keypoints`` (h, r_a, z_a, r_b, z_b).
"""
