"""The axisymmetric shell of revolution in scikit-fem: mesh, assembly, Newton solve.

Unknowns r(S) and z(S) over the rest radius S (mm) on a ``MeshLine``, each in cubic Hermite
elements (C1, as the curvature needs second derivatives). The energy is the integral of
``density.density``; its gradient and Hessian are assembled with scikit-fem forms from the
pointwise derivatives. Boundary conditions: r(0) = 0, z'(0) = 0 (pole), z(L) = 0 (gauge), with
L the reduced model's domain (N - 1) dR. The mesh has a node on the embroidery boundary R_b
(the coefficients jump there), ``elements_inside`` uniform elements on [0, R_b] and
geometrically growing elements outside; ``refine`` bisects every element that many times
(nested meshes for convergence studies).

The solve is Newton's method on the free dofs, certified by the max-norm of the free gradient,
with one of two globalizations. ``"diagonal"`` (the default, used from the reduced model's
equilibrium): an Armijo line search and a tenfold-growing diagonal shift when the Hessian is not
positive definite. ``"eigen"`` (used by the prestretch continuation, ``continuation.py``, far
from any equilibrium): the free Hessian, Jacobi-scaled and permuted to node order (a band of
half-width 7), is used as is when its banded Cholesky succeeds, else shifted by
2 |lambda_min| + 1e-12 with lambda_min its lowest eigenvalue (LAPACK's banded eigensolver), so
that the step descends and leaves saddles along negative curvature; the step is backtracked
until the energy satisfies Armijo and no meridional stretch
|(r', z')| (at the quadrature points and at the nodes) falls below half its value, which keeps
every stretch positive (the energy is +inf at zero stretch, but the pole's slope dof is not seen
by any quadrature point).
"""
from __future__ import annotations

import copy
import time
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
from scipy.interpolate import CubicSpline
from scipy.linalg import LinAlgError, cho_solve_banded, cholesky_banded, eig_banded, solveh_banded
from scipy.sparse.linalg import splu

from stitchswitch.errors import InvalidInputError, StitchSwitchError
from stitchswitch.fem_reference.density import density
from stitchswitch.reduced.model.discretization import fill_mixture, make_grid
from stitchswitch.reduced.model.params import Material, Patch

R_IDX, Z_IDX = (0, 1, 3), (2, 4)     # q = (r, r', z', r'', z''): r's (value, d, d2), z's (d, d2)
BAND = 7                 # half bandwidth of the Hessian in node order: 2 nodes x (r, r', z, z')
STRETCH_BOUND = 0.5      # "eigen": no step shrinks a meridional stretch below this fraction


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
        mix = fill_mixture(self.S < self.rb, patch.fill, material)
        self.coef = dict(
            lam=mix.lam, k_r=mix.k_r, k_theta=mix.k_theta, w_b=mix.w_b,
            w_log=material.w_log, gamma=material.gamma_mm, c=mix.compression, jam=material.jam,
            c_jam=material.c_jam,
            hoop=1.0 if hoop_bending else 0.0, nu=float(poisson))
        self.rest_lam = self.coef["lam"]           # the design's rest metric (t = 1)
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
        return self._energy_of(self._q(x))

    def _energy_of(self, q) -> float:
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

    # ----------------------------------------------------------------- prestretch
    def prestretched(self, t: float) -> "ShellModel":
        """The same model with the rest-metric excess scaled, lambda = 1 + t (lambda - 1): t = 0 is
        the flat, stress-free sheet, t = 1 the design (``self``). Shares the mesh and basis."""
        if t == 1.0:
            return self
        other = copy.copy(self)
        other.coef = dict(self.coef, lam=1.0 + t * (self.rest_lam - 1.0))
        return other

    def flat_state(self) -> np.ndarray:
        """The flat sheet at rest, r = S and z = 0 (stress free at t = 0)."""
        x = np.zeros(2 * self.n)
        x[self._value_dofs] = self.nodes
        x[self._deriv_dofs] = 1.0
        return x

    def stretches(self, x, q=None) -> np.ndarray:
        """Meridional stretch |(r', z')| at every quadrature point, then at every node (``q``:
        the fields at the quadrature points, if already computed)."""
        q = self._q(x) if q is None else q
        nodal = np.hypot(x[self._deriv_dofs], x[self.n + self._deriv_dofs])
        return np.concatenate([np.hypot(q[1], q[2]).ravel(), nodal])

    def _node_order(self) -> np.ndarray:
        """The free dofs sorted by mesh node (then r, r', z, z'): the Hessian becomes banded."""
        n, m = self.n, self.nodes.size
        node, kind = np.empty(2 * n, dtype=int), np.empty(2 * n, dtype=int)
        for k, dofs in enumerate((self._value_dofs, self._deriv_dofs,
                                  n + self._value_dofs, n + self._deriv_dofs)):
            node[dofs], kind[dofs] = np.arange(m), k
        free = self.free
        return free[np.lexsort((kind[free], node[free]))]

    @staticmethod
    def _scaled_band(H, order):
        """Jacobi scaling D and the lower band (LAPACK storage) of D^-1 H D^-1 on ``order``."""
        Hf = H[order][:, order].tocoo()
        diag = np.abs(Hf.diagonal())
        D = np.sqrt(np.maximum(diag, 1e-12 * max(float(diag.max()), 1e-300)))
        lower = Hf.row >= Hf.col
        rows, cols = Hf.row[lower], Hf.col[lower]
        if np.any(rows - cols > BAND):
            raise StitchSwitchError("the Hessian is not banded in node order")
        ab = np.zeros((BAND + 1, order.size))
        np.add.at(ab, (rows - cols, cols), Hf.data[lower] / (D[rows] * D[cols]))
        return D, ab

    def lowest_eigenvalue(self, x) -> float:
        """Lowest eigenvalue of the Jacobi-scaled free Hessian at ``x`` (> 0: a strict local
        minimum, up to round-off; the slack fabric's nearly free modes sit at ~1e-12)."""
        _, _, H = self.derivatives(x)
        _, ab = self._scaled_band(H, self._node_order())
        return float(eig_banded(ab, lower=True, select="i", select_range=(0, 0),
                                eigvals_only=True)[0])

    # ----------------------------------------------------------------- Newton
    def solve(self, x0, *, tol: float = 1e-9, max_iter: int = 100,
              globalization: str = "diagonal") -> ShellSolution:
        """Newton's method from ``x0``; ``globalization`` is ``"diagonal"`` or ``"eigen"``
        (module docstring)."""
        if globalization == "eigen":
            return self._solve_eigen(x0, tol, max_iter)
        if globalization != "diagonal":
            raise InvalidInputError(f"globalization: {globalization!r} is not 'diagonal' or 'eigen'")
        t0 = time.perf_counter()
        x = np.array(x0, dtype=float)
        free = self.free
        shift, it, converged = 0.0, 0, False
        E = self.energy(x)
        if not np.isfinite(E):
            raise InvalidInputError("the start is outside the energy's domain (a stretch or radius <= 0)")
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

    def _solution(self, x, E, residual, converged, it, t0) -> ShellSolution:
        n = self.n
        sol = ShellSolution(self.patch, self.nodes, x[:n][self._value_dofs], x[n:][self._value_dofs],
                            float(E), residual, converged, it, time.perf_counter() - t0, self)
        object.__setattr__(sol, "_x", x)
        return sol

    def _solve_eigen(self, x0, tol: float, max_iter: int) -> ShellSolution:
        """Newton with the Hessian shifted by its lowest eigenvalue, Armijo backtracking and the
        stretch bound (module docstring)."""
        t0 = time.perf_counter()
        x = np.array(x0, dtype=float)
        if not np.isfinite(self.energy(x)):
            raise InvalidInputError("the start is outside the energy's domain (a stretch or radius <= 0)")
        order = self._node_order()
        it = 0
        stretch = self.stretches(x)
        while True:
            E, g, H = self.derivatives(x)
            gf = g[order]
            residual = float(np.max(np.abs(gf)))
            if residual <= tol or it >= max_iter:
                break
            it += 1
            D, ab = self._scaled_band(H, order)
            gs = gf / D
            try:                             # positive definite: the plain Newton step
                step = cho_solve_banded((cholesky_banded(ab, lower=True), True), -gs)
            except LinAlgError:
                low = eig_banded(ab, lower=True, select="i", select_range=(0, 0),
                                 eigvals_only=True)[0]
                shift = max(-2.0 * low, 0.0) + 1e-12
                while True:                  # round-off can leave the shifted band indefinite
                    band = ab.copy()
                    band[0] += shift
                    try:
                        step = solveh_banded(band, -gs, lower=True)
                        break
                    except LinAlgError:
                        shift = max(10.0 * shift, 1e-10)
            slope = float(gs @ step)
            d = step / D
            floor = STRETCH_BOUND * stretch
            alpha, accepted = 1.0, False
            for _ in range(60):
                trial = x.copy()
                trial[order] += alpha * d
                q = self._q(trial)
                trial_stretch = self.stretches(trial, q)
                if np.all(trial_stretch >= floor):
                    E_new = self._energy_of(q)
                    if E_new <= E + 1e-4 * alpha * slope or (
                            np.isfinite(E_new) and -slope <= 1e-13 * abs(E)
                            and E_new <= E + 1e-12 * abs(E)):
                        accepted = True
                        break
                alpha *= 0.5
            if not accepted:
                break                                   # no admissible descent: give up
            x, stretch = trial, trial_stretch
        return self._solution(x, E, residual, residual <= tol, it, t0)
