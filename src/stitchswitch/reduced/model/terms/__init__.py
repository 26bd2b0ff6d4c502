"""Energy terms of the reduced model, one per module, each a ``protocol.Term``.

A term works on the node coordinates (r_i, z_i) in units of dR and carries its stencil and
offset, ``coefficients(grid)`` (computed once per design), ``energy(r, z, coef)`` and
``accumulate(r, z, coef, grad, hb)`` (gradient and banded Hessian in place); see ``protocol``.

* The model (Eq. 6 plus the compressive response and the trapezoid rule at the embroidery
  boundary): ``radial``, ``compression``, ``circumferential``, ``hardening``, ``boundary_ring``,
  ``bending``, each exposing ``TERM``; ``ALL_TERMS``.
* Physics the model leaves out, used by the discovery effects (``validation.discovery.effects``):
  ``extra/`` (``hoop_bending``, ``natural_curvature``, ``gravity``: factories ``term(...)``) and
  ``hardening.with_weight``.
* ``variants``: discretization variants kept for comparison (``PAPER_INDEXING``, the printed
  first-order quadrature of the boundary node's ring; the node-averaged hoop term).
* Shared kernels: ``segment`` (scattering into the global arrays), ``hinge`` (the chain rule of
  the hinge energies).

The loops are compiled with numba: for N = 300 a Python/numpy version spends its time in
per-call overhead (0.6 ms per Hessian against 0.06 ms compiled), and the calibration and the
design-space map need thousands of solves. Assembly is in ``..assembly``.
"""
from stitchswitch.reduced.model import kernel_cache

kernel_cache.guard()     # before any kernel is loaded from numba's cache (kernel_cache)

from stitchswitch.reduced.model.terms import (  # noqa: E402
    bending,
    boundary_ring,
    circumferential,
    compression,
    hardening,
    radial,
)
from stitchswitch.reduced.model.terms.protocol import Term  # noqa: E402

#: The terms of Eq. 6, the compressive response and the boundary's trapezoid rule, in assembly order.
ALL_TERMS = (radial.TERM, compression.TERM, circumferential.TERM, hardening.TERM, boundary_ring.TERM,
             bending.TERM)

__all__ = ["ALL_TERMS", "Term", "radial", "compression", "circumferential", "hardening", "boundary_ring",
           "bending"]
