"""The shell's total energy on the meridian's unknowns, with its exact gradient and Hessian.

Per side, at every quadrature point, the density per unit rest radius is

    f = lambda^2 S [membrane(eps_s, eps_t) + bending(k_s, k_t)] + hardening(eps_t)
        + q z r r' + g z S

(``constitutive``; the last two are loads: a pressure q pushing to -z, whose potential is q
times the enclosed volume / 2 pi, and a self weight g), and the energy is its quadrature sum
(the factor 2 pi of the azimuthal integral is dropped everywhere). The pointwise derivatives
come from jets (``jet``); the Hessian is assembled as B^T diag(w d2f) B with scikit-fem's
operators ``B`` of each side (``meridian``), the outer side through the interface map's
Jacobian and its second-derivative term. ``extras`` adds energies of the unknowns themselves
(a penalty, say). ``pinned`` unknowns are held at their values in the state (the nodes
under the contact plate of ``fem_reference.snap``).

Boundary conditions: r(0) = 0 and z'(0) = 0 at the pole; z(L) = 0 at the outer edge, where the
fabric is ``"free"`` (r(L) free, as the reduced model's far edge), ``"held"`` (r(L) = L: held
in a frame at its rest size, as in the switching experiment) or ``"clamped"`` (held, and
z'(L) = 0). ``t`` scales the natural metric's excess, lambda = 1 + t (lambda - 1) (t = 0: the
flat sheet is stress free).
"""
from __future__ import annotations

from dataclasses import replace

import numpy as np
import scipy.sparse as sp

from stitchswitch.errors import InvalidInputError
from stitchswitch.fem_reference.revolution import constitutive
from stitchswitch.fem_reference.revolution.jet import Jet
from stitchswitch.fem_reference.revolution.kinematics import strains
from stitchswitch.fem_reference.revolution.meridian import N_FIELDS, Meridian
from stitchswitch.fem_reference.revolution.moduli import Moduli

EDGES = ("free", "held", "clamped")


class ShellProblem:
    """Energy E(y) of a meridian with the moduli of its two regions."""

    def __init__(self, meridian: Meridian, inner: Moduli, outer: Moduli, *, edge: str = "free",
                 pressure: float = 0.0, weight: float = 0.0, t: float = 1.0, extras=(),
                 pinned=()):
        if edge not in EDGES:
            raise InvalidInputError(f"edge: {edge!r} is not one of {', '.join(EDGES)}")
        self.meridian, self.inner_moduli, self.outer_moduli = meridian, inner, outer
        self.edge, self.pressure, self.weight, self.t = edge, float(pressure), float(weight), float(t)
        self.extras = tuple(extras)
        self.pinned = tuple(int(i) for i in pinned)
        m = meridian
        last = m.outer_nodes.size - 1
        fixed = [m.dof("inner", "r", 0), m.dof("inner", "dz", 0), m.dof("outer", "z", last)]
        if edge in ("held", "clamped"):
            fixed.append(m.dof("outer", "r", last))
        if edge == "clamped":
            fixed.append(m.dof("outer", "dz", last))
        self.fixed = np.array(sorted(set(fixed) | set(self.pinned)))
        self.free = np.setdiff1d(np.arange(m.size), self.fixed)

    def with_(self, **changes) -> "ShellProblem":
        """The same problem with some of edge, pressure, weight, t, extras, pinned changed."""
        kw = dict(edge=self.edge, pressure=self.pressure, weight=self.weight, t=self.t,
                  extras=self.extras, pinned=self.pinned)
        kw.update(changes)
        return ShellProblem(self.meridian, self.inner_moduli, self.outer_moduli, **kw)

    # ------------------------------------------------------------------ pointwise
    def _moduli(self, m: Moduli) -> Moduli:
        return m if self.t == 1.0 else replace(m, lam=1.0 + self.t * (m.lam - 1.0))

    def _side_density(self, q: np.ndarray, S: np.ndarray, m: Moduli, derivatives: bool = True) -> Jet:
        m = self._moduli(m)
        eps_s, eps_t, k_s, k_t = strains(q, S, m.lam, derivatives)
        w = (constitutive.membrane(eps_s, eps_t, m) + constitutive.bending(k_s, k_t, m)) * (m.lam ** 2 * S)
        w = w + constitutive.hoop_hardening(eps_t, S, m)
        if self.pressure or self.weight:
            z = Jet.variable(q, 5, derivatives)
            r, rp = Jet.variable(q, 0, derivatives), Jet.variable(q, 1, derivatives)
            w = w + z * r * rp * self.pressure + z * S * self.weight
        return w

    @staticmethod
    def _in_domain(q: np.ndarray) -> bool:
        return bool(np.all(q[0] > 0.0) and np.all(q[1] ** 2 + q[2] ** 2 > 0.0))

    def _side(self, side, x, m: Moduli, want: int):
        q6 = (side.B @ x).reshape(N_FIELDS, -1)
        if not self._in_domain(q6):
            return np.inf, None, None
        f = self._side_density(q6, side.S, m, want > 0)    # jets in all six fields (z: loads)
        E = float(np.sum(f.v * side.w))
        if not np.isfinite(E):
            return np.inf, None, None
        if want == 0:
            return E, None, None
        g = side.B.T @ (f.g * side.w).ravel()
        if want == 1:
            return E, g, None
        M, pattern = side.hessian_map
        H = pattern.copy()
        H.data = M @ (f.h * side.w).ravel()
        return E, g, H

    # ------------------------------------------------------------------ totals
    def energy(self, y: np.ndarray) -> float:
        return self.evaluate(y, 0)[0]

    def derivatives(self, y: np.ndarray):
        """(E, gradient, Hessian (sparse, symmetric)) at ``y``."""
        return self.evaluate(y, 2)

    def evaluate(self, y: np.ndarray, want: int = 2):
        mer = self.meridian
        if y[mer.s_index] <= 0.0:
            return np.inf, None, None
        Ei, gi, Hi = self._side(mer.inner, mer.inner_x(y), self.inner_moduli, want)
        if not np.isfinite(Ei):
            return np.inf, None, None
        Eo, go, Ho = self._side(mer.outer, mer.outer_x(y), self.outer_moduli, want)
        if not np.isfinite(Eo):
            return np.inf, None, None
        E = Ei + Eo
        g = H = None
        if want:
            ni2 = 2 * mer.inner.n
            J = mer.outer_jacobian(y)
            g = J.T @ go
            g[:ni2] += gi
            if want == 2:
                H = J.T @ Ho @ J + mer.outer_second(go)
                H = H + sp.block_diag([Hi, sp.csr_matrix((mer.size - ni2,) * 2)], format="csr")
        for extra in self.extras:
            e, ge, He = extra.evaluate(y, want)
            E += e
            if want:
                g = g + ge
            if want == 2:
                H = H + He
        return E, g, (H.tocsr() if H is not None else None)

    # ------------------------------------------------------------------ states
    def flat_state(self) -> np.ndarray:
        """r = S, z = 0 (the flat, relaxed sheet: stress free at t = 0)."""
        m = self.meridian
        xi = np.zeros(2 * m.inner.n)
        xi[m.inner.value] = m.inner_nodes
        xi[m.inner.slope] = 1.0
        xo = np.zeros(2 * m.outer.n)
        xo[m.outer.value] = m.outer_nodes
        xo[m.outer.slope] = 1.0
        return m.from_sides(xi, xo)
