"""Energy terms of the reduced model, one per module.

Every term works on the node coordinates (r_i, z_i) in units of dR and exposes

* ``STENCIL`` (nodes per element) and ``OFFSET`` (first node of the first element),
* ``coefficients(grid)``: its per-element coefficients for one design, computed once,
* ``energy(r, z, coef) -> float`` (+inf outside the term's domain),
* ``accumulate(r, z, coef, grad, hb) -> float``: adds its gradient into ``grad`` (2N,) and,
  if ``hb`` has columns, its Hessian into the lower band ``hb`` (6, 2N); returns its energy.

The loops are compiled with numba: for N = 300 a Python/numpy version spends its time in
per-call overhead (0.6 ms per Hessian against 0.06 ms compiled), and the calibration and the
design-space map need thousands of solves. Assembly is in ``..assembly``.
"""
from stitchswitch.reduced.model.terms import bending, circumferential, compression, hardening, radial

#: The terms of Eq. 6 plus the slack regularization, in assembly order.
ALL_TERMS = (radial, compression, circumferential, hardening, bending)

__all__ = ["ALL_TERMS", "radial", "compression", "circumferential", "hardening", "bending"]
