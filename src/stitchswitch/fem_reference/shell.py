"""The axisymmetric shell of revolution in scikit-fem: mesh, assembly, Newton solve.

Unknowns r(S) and z(S) over the rest radius S (mm) on a ``MeshLine``, each in cubic Hermite
elements (C1, as the curvature needs second derivatives). The energy is the integral of
``density.density``; its gradient and Hessian are assembled with scikit-fem forms from the
pointwise derivatives. Boundary conditions: r(0) = 0, z'(0) = 0 (pole), z(L) = 0 (gauge), with
L the reduced model's domain (N - 1) dR. The mesh has a node on the embroidery boundary R_b
(the coefficients jump there), ``elements_inside`` uniform elements on [0, R_b] and
geometrically growing elements outside; ``refine`` bisects every element that many times
(nested meshes for convergence studies).

The solve is Newton's method on the free dofs with an Armijo line search and a tenfold-growing
diagonal shift when the Hessian is not positive definite; it starts from the reduced model's
equilibrium of the same design (the same branch), and its certificate is the max-norm of the
free gradient.
"""
from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
from scipy.interpolate import CubicSpline
from scipy.sparse.linalg import splu

from stitchswitch.fem_reference.density import density
from stitchswitch.reduced.discretization import make_grid
from stitchswitch.reduced.params import Material, Patch

R_IDX, Z_IDX = (0, 1, 3), (2, 4)     # q = (r, r', z', r'', z''): r's (value, d, d2), z's (d, d2)


def shell_mesh_nodes(rb: float, length: float, elements_inside: int, growth: float = 1.08) -> np.ndarray:
    """Uniform on [0, rb], then geometrically growing sizes up to ``length``."""
    inside = np.linspace(0.0, rb, elements_inside + 1)
    h = rb / elements_inside
    outside = [rb]
    while outside[-1] < length:
        h *= growth
        outside.append(min(outside[-1] + h, length))
        if length - outside[-1] < 0.5 * h:
            outside[-1] = length
    return np.concatenate([inside, np.array(outside[1:])])


@dataclass(frozen=True)
class ShellSolution:
    patch: Patch
    S_mm: np.ndarray           # mesh nodes
    r_mm: np.ndarray           # r at the nodes
    z_mm: np.ndarray           # z at the nodes
    energy: float
    residual: float
    converged: bool
    iterations: int
    solve_s: float
    model: "ShellModel"

    def sample(self, spacing_mm: float | None = None):
        """(R, r, z, n_inside): the profile on a uniform grid with a node on R_b."""
        return self.model.sample(self._x, spacing_mm)


class ShellModel:
    def __init__(self, patch: Patch, material: Material, *, elements_inside: int = 40,
                 growth: float = 1.08, hoop_bending: bool = False, poisson: float = 0.0,
                 intorder: int = 6, refine: int = 0):
        from skfem import Basis, ElementLineHermite, MeshLine

        grid = make_grid(patch, material)
        self.patch, self.material = patch, material
        self.rb = patch.diameter_mm / (2.0 * material.eta)
        self.length = (material.n_nodes - 1) * grid.dr_mm
        nodes = shell_mesh_nodes(self.rb, self.length, elements_inside, growth)
        for _ in range(refine):                    # nested uniform refinement (bisection)
            nodes = np.sort(np.concatenate([nodes, 0.5 * (nodes[1:] + nodes[:-1])]))
        self.basis = Basis(MeshLine(nodes), ElementLineHermite(), intorder=intorder)
        b = self.basis
        self.nodes = nodes
        self.S = np.asarray(b.global_coordinates())[0]
        inside = self.S < self.rb
        p2 = patch.fill ** 2

        def piece(emb, fab):
            return np.where(inside, emb * p2 + fab * (1 - p2), fab)

        self.coef = dict(
            lam=np.where(inside, 1.0 + (material.eta - 1.0) * p2, 1.0),
            k_r=piece(material.k_r_emb, material.k_r_fab),
            k_theta=piece(material.k_theta_emb, material.k_theta_fab),
            w_b=piece(material.w_b_emb, material.w_b_fab),
            w_log=material.w_log, gamma=material.gamma_mm, c=material.compression_ratio,
            hoop=1.0 if hoop_bending else 0.0, nu=float(poisson))
        n = b.N
        self.n = n
        value, deriv = b.nodal_dofs[0], b.nodal_dofs[1]
        fixed = np.array([value[0], n + deriv[0], n + value[-1]])   # r(0), z'(0), z(L)
        self.free = np.setdiff1d(np.arange(2 * n), fixed)
        self._value_dofs, self._deriv_dofs = value, deriv

    # ----------------------------------------------------------------- fields and energy
    def _q(self, x):
        n = self.n
        R, Z = self.basis.interpolate(x[:n]), self.basis.interpolate(x[n:])
        return np.array([np.asarray(R), R.grad[0], Z.grad[0], R.hess[0, 0], Z.hess[0, 0]])

    def energy(self, x) -> float:
        q = self._q(x)
        if np.any(q[0] <= 0) or np.any(np.hypot(q[1], q[2]) <= 0):
            return np.inf
        f, _, _ = density(q, self.S, self.coef, hessian=False)
        val = float(np.sum(f * self.basis.dx))
        return val if np.isfinite(val) else np.inf

    def derivatives(self, x):
        from skfem import BilinearForm, LinearForm, asm

        b = self.basis
        f, g, H = density(self._q(x), self.S, self.coef)
        D = lambda v: (v, v.grad[0], v.hess[0, 0])              # noqa: E731
        Dz = lambda v: (v.grad[0], v.hess[0, 0])                # noqa: E731

        @LinearForm
        def grad_r(v, w):
            return sum(w[f"g{a}"] * d for a, d in zip(R_IDX, D(v)))

        @LinearForm
        def grad_z(v, w):
            return sum(w[f"g{a}"] * d for a, d in zip(Z_IDX, Dz(v)))

        def block(rows, cols, drow, dcol):
            @BilinearForm
            def form(u, v, w):
                return sum(w[f"h{a}{c}"] * dr * dc for a, dr in zip(rows, drow(v))
                           for c, dc in zip(cols, dcol(u)))
            return form

        gw = {f"g{a}": g[a] for a in range(5)}
        hw = {f"h{a}{c}": H[a, c] for a in range(5) for c in range(5)}
        grad = np.concatenate([asm(grad_r, b, **gw), asm(grad_z, b, **gw)])
        Hrr = asm(block(R_IDX, R_IDX, D, D), b, **hw)
        Hzr = asm(block(Z_IDX, R_IDX, Dz, D), b, **hw)
        Hzz = asm(block(Z_IDX, Z_IDX, Dz, Dz), b, **hw)
        hess = sp.bmat([[Hrr, Hzr.T], [Hzr, Hzz]], format="csc")
        return float(np.sum(f * b.dx)), grad, hess

    # ----------------------------------------------------------------- start and sampling
    def start_from_profile(self, R_mm, r_mm, z_mm) -> np.ndarray:
        """Hermite dofs interpolating a profile (values and slopes by a cubic spline)."""
        x = np.zeros(2 * self.n)
        for k, prof in enumerate((r_mm, z_mm)):
            spline = CubicSpline(R_mm, prof)
            S = np.clip(self.nodes, R_mm[0], R_mm[-1])
            x[k * self.n + self._value_dofs] = spline(S)
            x[k * self.n + self._deriv_dofs] = spline(S, 1)
        x[self._value_dofs[0]] = 0.0
        x[self.n + self._deriv_dofs[0]] = 0.0
        x[self.n + self._value_dofs] -= x[self.n + self._value_dofs[-1]]
        return x

    def sample(self, x, spacing_mm: float | None = None):
        """Profile on points S = i * spacing with a point exactly on R_b; returns
        (R, r, z, n_inside)."""
        n_in = max(int(np.ceil(self.rb / (spacing_mm or self.rb / 200.0))), 1)
        step = self.rb / n_in
        R = np.minimum(np.arange(0.0, self.length + 1e-9, step), self.nodes[-1])
        probes = self.basis.probes(R[None, :])
        n = self.n
        return R, probes @ x[:n], probes @ x[n:], n_in

    # ----------------------------------------------------------------- Newton
    def solve(self, x0, *, tol: float = 1e-9, max_iter: int = 100) -> ShellSolution:
        t0 = time.perf_counter()
        x = np.array(x0, dtype=float)
        free = self.free
        shift, it, converged = 0.0, 0, False
        E = self.energy(x)
        if not np.isfinite(E):
            raise ValueError("the start is outside the energy's domain")
        while True:
            E, g, H = self.derivatives(x)
            gf = g[free]
            residual = float(np.max(np.abs(gf)))
            if residual <= tol:
                converged = True
                break
            if it >= max_iter:
                break
            it += 1
            Hf = H[free][:, free].tocsc()
            scale = float(np.mean(np.abs(Hf.diagonal()))) or 1.0
            shift = shift / 10.0 if shift > 1e-12 * scale else 0.0
            for _ in range(40):
                A = Hf + shift * sp.identity(free.size, format="csc")
                try:
                    d = -splu(A).solve(gf)
                except RuntimeError:
                    d = None
                if d is not None and gf @ d < 0 and d @ (Hf @ d) > 0:
                    break
                shift = max(10.0 * shift, 1e-8 * scale)
            else:
                break                                   # no descent direction: give up
            alpha, accepted = 1.0, False
            for _ in range(50):
                trial = x.copy()
                trial[free] += alpha * d
                E_new = self.energy(trial)
                if E_new <= E + 1e-4 * alpha * float(gf @ d) or (
                        np.isfinite(E_new) and abs(gf @ d) < 1e-13 * abs(E)):
                    accepted = True
                    break
                alpha *= 0.5
            if not accepted:
                break
            x = trial
        n = self.n
        sol = ShellSolution(self.patch, self.nodes, x[:n][self._value_dofs], x[n:][self._value_dofs],
                            float(E), residual, converged, it, time.perf_counter() - t0, self)
        object.__setattr__(sol, "_x", x)
        return sol
