"""Energy terms of the reduced model, one per module.

Every term works on the node coordinates (r_i, z_i) in units of dR and exposes
``STENCIL`` (nodes per element), ``OFFSET`` (first node of the first element; element j
covers nodes OFFSET + j .. OFFSET + j + STENCIL - 1), ``energy(r, z, grid) -> float`` and
``local(r, z, grid) -> (e, g, H)``: per-element energies (n,), gradients (n, 2S) and Hessians
(n, 2S, 2S) with local dofs ordered (r, z) node by node. Assembly is in ``..assembly``.
"""
from stitchswitch.reduced.terms import bending, circumferential, compression, hardening, radial

#: The terms of Eq. 6 plus the slack regularization, in assembly order.
ALL_TERMS = (radial, compression, circumferential, hardening, bending)

__all__ = ["ALL_TERMS", "radial", "compression", "circumferential", "hardening", "bending"]
