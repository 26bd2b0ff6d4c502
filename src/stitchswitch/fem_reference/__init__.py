"""Finite-element references that check the reduced model (docs/fem-reference.md).

* ``revolution/``: the independent reference, an axisymmetric Kirchhoff-Love shell of
  revolution in scikit-fem (its own kinematics, tension-field knit, Poisson, hoop bending,
  natural curvature, the embroidery boundary as a material interface), its constants mapped
  from the reduced model's ``Material``;
* ``model_error/``: ``stitchswitch fem-check``, the reduced model against that shell with the
  gap attributed to each missing physics, judged against a model-error budget;
* ``snap/``: snap-through by a contact plate as in the paper's experiment (switching force in N,
  energy barrier, the switched state) and bistable or spring-back
  (``stitchswitch switch-force``, ``stitchswitch bistability-map``);
* the same-energy discretization check, kept as a test of the reduced discretization (and used
  by ``validation.discovery.synthetic``): ``density`` (the reduced model's continuum limit),
  ``shell`` (its Hermite discretization), ``continuation`` (its prestretch continuation),
  ``check`` (the convergence of the reduced model to it).
"""
