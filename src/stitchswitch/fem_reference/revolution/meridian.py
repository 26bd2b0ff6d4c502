"""The meridian's finite elements: two scikit-fem meshes that meet at the embroidery boundary,
and the map from the unknowns to the fields at the quadrature points.

r(S) and z(S) are cubic Hermite (C1) on each side: ``elements_inside`` uniform elements on
[0, R_b] (the embroidered disc) and geometrically growing ones on [R_b, L] (the bare knit). The
boundary is a double node, a true material interface: r and z are shared, and the outer side's
slope is s times the inner side's, (r', z')_+ = s (r', z')_-, with s > 0 an unknown. So the
tangent angle is continuous (Kirchhoff-Love: no kink), while the meridional stretch l jumps by
the factor s, as the exact solution's does where the natural metric and the stiffness jump.

Unknowns y = (inner r dofs, inner z dofs, outer r dofs, outer z dofs without the interface
node's four, s). ``side_dofs`` gives each side's scikit-fem dof vector (r dofs, then z dofs) and
its Jacobian with respect to y, ``operators`` the sparse matrices from a side's dofs to
(r, r', z', r'', z'', z) at its quadrature points.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

#: Order of the point fields (kinematics.FIELDS, then z for the loads).
N_FIELDS = 6


def outer_nodes(rb: float, length: float, h0: float, growth: float) -> np.ndarray:
    """Nodes from ``rb`` to ``length``, sizes growing geometrically from ``h0``."""
    nodes, h = [rb], h0
    while nodes[-1] < length - 1e-12:
        nodes.append(min(nodes[-1] + h, length))
        if length - nodes[-1] < 0.5 * h:
            nodes[-1] = length
        h *= growth
    return np.array(nodes)


@dataclass
class Side:
    """One side's scikit-fem basis, its quadrature points (rest radius ``S``, weights ``w``) and
    the operator ``B`` (6 P, 2 N) from its dofs (r dofs, z dofs) to the six point fields."""

    basis: object
    S: np.ndarray
    w: np.ndarray
    B: sp.csr_matrix
    value: np.ndarray     # value dofs, by node
    slope: np.ndarray     # slope dofs, by node
    hessian_map: tuple = None   # (M, pattern): see ``_hessian_map``

    @property
    def n(self) -> int:
        return self.basis.N


def _side(nodes: np.ndarray, intorder: int) -> Side:
    from skfem import Basis, ElementLineHermite, MeshLine

    basis = Basis(MeshLine(nodes), ElementLineHermite(), intorder=intorder)
    ne, nq = basis.dx.shape
    p = ne * nq
    n = basis.N
    # per field: the dof (P, nbfun) and the basis function's value (P, nbfun) at every point
    cols = np.zeros((N_FIELDS, p, basis.Nbfun), dtype=int)
    vals = np.zeros((N_FIELDS, p, basis.Nbfun))
    for i in range(basis.Nbfun):
        f = basis.basis[i][0]
        dof = np.repeat(basis.element_dofs[i][:, None], nq, axis=1).ravel()
        comps = {0: (np.asarray(f), 0), 1: (f.grad[0], 0), 3: (f.hess[0, 0], 0),
                 5: (np.asarray(f), n), 2: (f.grad[0], n), 4: (f.hess[0, 0], n)}
        for field, (val, off) in comps.items():
            cols[field, :, i] = dof + off
            vals[field, :, i] = np.asarray(val).ravel()
    rows = np.broadcast_to((np.arange(N_FIELDS)[:, None, None] * p + np.arange(p)[None, :, None]),
                           cols.shape)
    B = sp.csr_matrix((vals.ravel(), (rows.ravel(), cols.ravel())), shape=(N_FIELDS * p, 2 * n))
    S = np.asarray(basis.global_coordinates())[0].ravel()
    side = Side(basis, S, np.asarray(basis.dx).ravel(), B, basis.nodal_dofs[0], basis.nodal_dofs[1])
    side.hessian_map = _hessian_map(cols, vals, 2 * n)
    return side


def _hessian_map(cols: np.ndarray, vals: np.ndarray, n: int):
    """The fixed linear map from the pointwise weighted Hessians hw (6, 6, P), flattened, to the
    data of B^T diag(hw) B in a fixed sparsity pattern: (M, pattern) with H.data = M @ hw.ravel().
    ``cols``, ``vals`` (6, P, k): each field's dofs and basis values at every point."""
    nf, p, k = cols.shape
    ii = np.broadcast_to(cols[:, None, :, :, None], (nf, nf, p, k, k))
    jj = np.broadcast_to(cols[None, :, :, None, :], (nf, nf, p, k, k))
    vv = vals[:, None, :, :, None] * vals[None, :, :, None, :]
    src = np.broadcast_to(np.arange(nf * nf * p).reshape(nf, nf, p)[:, :, :, None, None], vv.shape)
    rows, cols_, vals_, src = ii.ravel(), jj.ravel(), vv.ravel(), src.ravel()
    pattern = sp.csr_matrix((np.ones(rows.size), (rows, cols_)), shape=(n, n))
    pattern.sum_duplicates()
    pattern.sort_indices()
    lookup = sp.csr_matrix((np.arange(pattern.nnz) + 1.0, pattern.indices, pattern.indptr), shape=(n, n))
    pos = np.asarray(lookup[rows, cols_]).ravel().astype(int) - 1
    M = sp.csr_matrix((vals_, (pos, src)), shape=(pattern.nnz, nf * nf * p))
    return M, pattern


class Meridian:
    """Both sides, the unknown vector's layout and the interface map."""

    def __init__(self, rb: float, length: float, elements_inside: int, growth: float,
                 intorder: int, refine: int = 0):
        inner = np.linspace(0.0, rb, elements_inside + 1)
        outer = outer_nodes(rb, length, rb / elements_inside, growth)
        for _ in range(refine):                       # nested bisection of every element
            inner = np.sort(np.concatenate([inner, 0.5 * (inner[1:] + inner[:-1])]))
            outer = np.sort(np.concatenate([outer, 0.5 * (outer[1:] + outer[:-1])]))
        self.rb, self.length = rb, float(outer[-1])
        self.inner_nodes, self.outer_nodes = inner, outer
        self.inner, self.outer = _side(inner, intorder), _side(outer, intorder)
        ni, no = self.inner.n, self.outer.n
        o = self.outer
        iface = np.array([o.value[0], o.slope[0], no + o.value[0], no + o.slope[0]])
        self._outer_kept = np.setdiff1d(np.arange(2 * no), iface)
        self.size = 2 * ni + self._outer_kept.size + 1
        self.s_index = self.size - 1
        # inner dofs of the interface node (last inner node)
        i = self.inner
        self.iface_inner = dict(r=i.value[-1], dr=i.slope[-1], z=ni + i.value[-1], dz=ni + i.slope[-1])
        self.iface_outer = dict(r=o.value[0], dr=o.slope[0], z=no + o.value[0], dz=no + o.slope[0])
        # constant part of the outer side's Jacobian: the kept dofs and the shared values
        rows = list(self._outer_kept) + [self.iface_outer["r"], self.iface_outer["z"]]
        cols = list(2 * ni + np.arange(self._outer_kept.size)) + [self.iface_inner["r"],
                                                                  self.iface_inner["z"]]
        self._T = sp.csr_matrix((np.ones(len(rows)), (rows, cols)), shape=(2 * no, self.size))

    # ------------------------------------------------------------------ layout
    def inner_x(self, y: np.ndarray) -> np.ndarray:
        return y[:2 * self.inner.n]

    def outer_x(self, y: np.ndarray) -> np.ndarray:
        x = self._T @ y
        s = y[self.s_index]
        x[self.iface_outer["dr"]] = s * y[self.iface_inner["dr"]]
        x[self.iface_outer["dz"]] = s * y[self.iface_inner["dz"]]
        return x

    def outer_jacobian(self, y: np.ndarray) -> sp.csr_matrix:
        s = y[self.s_index]
        fi, fo = self.iface_inner, self.iface_outer
        extra = sp.csr_matrix(
            ([s, y[fi["dr"]], s, y[fi["dz"]]],
             ([fo["dr"], fo["dr"], fo["dz"], fo["dz"]], [fi["dr"], self.s_index, fi["dz"], self.s_index])),
            shape=self._T.shape)
        return (self._T + extra).tocsr()

    def outer_second(self, g_outer: np.ndarray) -> sp.csr_matrix:
        """The interface map's second-derivative term: sum_k g_k d2 x_k / dy2 (symmetric)."""
        fi, fo, s = self.iface_inner, self.iface_outer, self.s_index
        a, b = g_outer[fo["dr"]], g_outer[fo["dz"]]
        return sp.csr_matrix(([a, a, b, b], ([s, fi["dr"], s, fi["dz"]], [fi["dr"], s, fi["dz"], s])),
                             shape=(self.size, self.size))

    def from_sides(self, x_inner: np.ndarray, x_outer: np.ndarray) -> np.ndarray:
        """y from both sides' dof vectors (s from the ratio of the interface slopes)."""
        y = np.zeros(self.size)
        y[:x_inner.size] = x_inner
        y[2 * self.inner.n:self.s_index] = x_outer[self._outer_kept]
        fi, fo = self.iface_inner, self.iface_outer
        din = np.hypot(x_inner[fi["dr"]], x_inner[fi["dz"]])
        dout = np.hypot(x_outer[fo["dr"]], x_outer[fo["dz"]])
        y[self.s_index] = dout / din if din > 0 else 1.0
        return y

    # ------------------------------------------------------------------ named dofs
    def dof(self, side: str, field: str, node: int) -> int:
        """Index in y of a side's nodal dof (field 'r', 'dr', 'z', 'dz'); the outer side's
        interface node maps to the inner side's (values) and is refused for slopes."""
        if side == "inner":
            s = self.inner
            n = s.n
            local = (s.value if field in ("r", "z") else s.slope)[node] + (n if field in ("z", "dz") else 0)
            return int(local)
        o = self.outer
        node = node % self.outer_nodes.size
        if node == 0:
            if field in ("dr", "dz"):
                raise ValueError("the interface slopes are s times the inner ones")
            return self.iface_inner[field]
        local = (o.value if field in ("r", "z") else o.slope)[node] + (o.n if field in ("z", "dz") else 0)
        return int(2 * self.inner.n + np.searchsorted(self._outer_kept, local))

    def node_values(self, y: np.ndarray):
        """(S, r, z) at every mesh node, the interface once."""
        xi, xo = self.inner_x(y), self.outer_x(y)
        ni, no = self.inner.n, self.outer.n
        S = np.concatenate([self.inner_nodes, self.outer_nodes[1:]])
        r = np.concatenate([xi[self.inner.value], xo[self.outer.value[1:]]])
        z = np.concatenate([xi[ni + self.inner.value], xo[no + self.outer.value[1:]]])
        return S, r, z

    def sample(self, y: np.ndarray, spacing_mm: float):
        """(S, r, z, n_inside) on points spaced about ``spacing_mm`` with one exactly on R_b."""
        n_in = max(int(np.ceil(self.rb / spacing_mm)), 1)
        S_in = np.linspace(0.0, self.rb, n_in + 1)
        step = self.rb / n_in
        S_out = np.arange(self.rb + step, self.length + 1e-9, step)
        S_out = S_out[S_out <= self.length]
        xi, xo = self.inner_x(y), self.outer_x(y)
        pi = self.inner.basis.probes(S_in[None, :])
        po = self.outer.basis.probes(np.clip(S_out, self.rb, self.length)[None, :])
        ni, no = self.inner.n, self.outer.n
        r = np.concatenate([pi @ xi[:ni], po @ xo[:no]])
        z = np.concatenate([pi @ xi[ni:], po @ xo[no:]])
        return np.concatenate([S_in, S_out]), r, z, n_in
