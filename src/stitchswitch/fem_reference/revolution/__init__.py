"""The independent reference: an axisymmetric Kirchhoff-Love shell of revolution in
scikit-fem (docs/fem-reference.md).

It is not the reduced model's energy: it has the exact strains and both curvatures of a shell of
revolution (``kinematics``), Poisson coupling, hoop bending, a natural curvature of the
embroidered layer, a tension-field (Pipkin-relaxed) membrane for the bare knit
(``constitutive``), and the embroidery boundary as a true material interface (a double node
where the stretch jumps, ``meridian``). Its constants are mapped from the reduced model's
calibrated ``Material`` (``moduli``) plus its own ``ShellParams`` (``params``).

Public API:

* ``ShellParams``, ``DEFAULT_SHELL``, ``SWITCHES`` (``params``);
* ``build(patch, material, params, edge=...) -> ShellProblem`` and
  ``equilibrium(...) -> ShellState`` (``solve``): certified Newton solves, keypoints, energies;
* ``ShellProblem`` (``problem``): energy, exact gradient and Hessian of the unknowns;
* ``minimize``, ``lowest_eigenvalue`` (``newton``);
* ``force_scale_n_per_model`` (``moduli``): newtons per model force unit.
"""
from stitchswitch.fem_reference.revolution.moduli import force_scale_n_per_model
from stitchswitch.fem_reference.revolution.newton import lowest_eigenvalue, minimize
from stitchswitch.fem_reference.revolution.params import DEFAULT_SHELL, SWITCHES, ShellParams
from stitchswitch.fem_reference.revolution.problem import ShellProblem
from stitchswitch.fem_reference.revolution.solve import ShellState, build, equilibrium

__all__ = ["DEFAULT_SHELL", "SWITCHES", "ShellParams", "ShellProblem", "ShellState", "build",
           "equilibrium", "force_scale_n_per_model", "lowest_eigenvalue", "minimize"]
