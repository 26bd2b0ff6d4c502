"""The paper's discretization of the rest radius (section 4, "Discretization").

Nodes i = 0..N-1 sit at R_i = i dR with dR = (d / 2 eta) / N_in and
N_in = ceil((d / 2 eta) / dR_max), so node N_in lies exactly on the embroidery boundary.

Small patches. Read literally, the rule gives a 15 mm patch 9 nodes inside and a fabric domain
of 33 patch radii: the buckling of the patch is under-resolved (h moves by 10-300 % under
refinement below d = 20 mm) while the far fabric is needlessly long. We therefore also require
N_in >= (N - 1) / domain_max_rb (default 7.5): the domain is at most 7.5 R_b and a small patch
gets a finer spacing, dR < dR_max, which the paper's "maximum spacing" allows. Patches with
d >= 2 eta dR_max (N - 1) / 7.5 (68 mm at the defaults) are discretized exactly as printed.
Everything here is in units of dR: R_i = i.

Segment i joins nodes i and i+1 (i = 0..N-2). Segment i is *inside* the embroidery iff
i < N_in, i.e. iff both of its nodes lie in the closed disc R <= d / 2 eta. (Read literally,
the paper's test R^(i) <= d / 2 eta would also put segment N_in, the first one outside, inside.)
The per-segment rest metric lambda and stiffnesses k follow the paper, weighted by p^2
(``fill_mixture``, also used by the shell reference):

    lambda = 1 + (eta - 1) p^2,   k = k_emb p^2 + k_fab (1 - p^2)   inside,
    lambda = 1,                   k = k_fab                         outside.

The bending hinge i sits at node i+1, between segments i and i+1 (i = 0..N-3), and uses the
weight of segment i, so the hinge on the boundary node N_in is inside.

Units. In dR units the membrane terms are the physical membrane energy divided by dR^2, but
the bending term (tan^2 of an angle times a length ratio) is the same in any unit. Left alone,
the ratio of bending to membrane stiffness would scale with dR^2, i.e. change with d through the
adaptive spacing, and every design with the same N_in would have the same shape in dR units:
h(d) becomes a staircase with a jump at every change of N_in (6 % at d = 25 mm). The bending
weights are therefore those at the reference spacing ``BENDING_REFERENCE_MM`` (the paper's
0.5 mm) and are scaled by ``bending_scale = (0.5 mm / dR)^2``; likewise the hardening limit is a
length, ``gamma = gamma_mm / dR``. Then the discrete energy is (1/dR^2) times one
dR-independent functional, and refining the grid converges to its minimizer.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from stitchswitch.errors import InvalidInputError
from stitchswitch.reduced.model.params import Material, Patch


@dataclass(frozen=True)
class Grid:
    """Per-segment coefficients of one design, in dR units. Arrays are read-only."""

    n_nodes: int
    n_inside: int          # N_in: index of the node on the embroidery boundary
    dr_mm: float           # dR in mm
    lam: np.ndarray        # (N-1,) rest metric of each segment
    k_r: np.ndarray        # (N-1,) radial stiffness
    k_theta: np.ndarray    # (N-1,) circumferential stiffness
    w_b: np.ndarray        # (N-2,) bending weight of hinge i (node i+1), material value
    w_log: float
    gamma: float           # hardening limit, dR units
    compression: np.ndarray  # (N-1,) compressive stiffness ratio c of each segment, floor included
    jam: float             # jamming stretch: the knit resists compression past l / lambda = jam
    c_jam: float           # the jammed knit's compressive stiffness / its tensile stiffness
    bending_scale: float   # (dR_max / dR)^2: makes the bending length independent of dR

    @property
    def R(self) -> np.ndarray:
        """Rest radius of every node, dR units."""
        return np.arange(self.n_nodes, dtype=float)

    @property
    def inside(self) -> np.ndarray:
        return np.arange(self.n_nodes - 1) < self.n_inside

    def with_lambda_scale(self, t: float) -> "Grid":
        """The same grid with the rest-metric excess scaled: lambda = 1 + t (lambda - 1).

        Used by the release continuation (t from 0, flat and stress free, to 1)."""
        lam = 1.0 + t * (self.lam - 1.0)
        lam.setflags(write=False)
        return Grid(self.n_nodes, self.n_inside, self.dr_mm, lam, self.k_r, self.k_theta,
                    self.w_b, self.w_log, self.gamma, self.compression, self.jam, self.c_jam,
                    self.bending_scale)


#: Node spacing at which the bending weights are defined: the paper's dR_max. A constant, so
#: that refining the grid (a smaller ``dr_max_mm``) changes the resolution, not the material.
BENDING_REFERENCE_MM = 0.5


def _ro(a: np.ndarray) -> np.ndarray:
    a = np.ascontiguousarray(a, dtype=float)
    a.setflags(write=False)
    return a


def min_inside(material: Material) -> int:
    """The fewest nodes inside any patch: (N - 1) dR <= domain_max_rb R_b."""
    return max(1, math.ceil((material.n_nodes - 1) / material.domain_max_rb - 1e-12))


def n_inside(patch: Patch, material: Material) -> int:
    """N_in = max(ceil((d / 2 eta) / dR_max), min_inside(material)), guarded against round-off
    at exact multiples."""
    ratio = patch.diameter_mm / (2.0 * material.eta) / material.dr_max_mm
    n = math.ceil(ratio - 1e-12)
    return max(n, min_inside(material))


def n_inside_array(diameters_mm: np.ndarray, material: Material) -> np.ndarray:
    """``n_inside`` for an array of diameters (same rule, vectorized)."""
    ratio = np.asarray(diameters_mm, dtype=float) / (2.0 * material.eta) / material.dr_max_mm
    return np.maximum(np.ceil(ratio - 1e-12), min_inside(material)).astype(int)


@dataclass(frozen=True)
class FillMixture:
    """Rest metric and stiffnesses of the embroidered fabric at a set of points."""

    lam: np.ndarray
    k_r: np.ndarray
    k_theta: np.ndarray
    w_b: np.ndarray
    compression: np.ndarray


def fill_mixture(inside: np.ndarray, fill: float, material: Material) -> FillMixture:
    """The paper's fill-mixture law, weighted by p^2: lambda = 1 + (eta - 1) p^2 and
    k = k_emb p^2 + k_fab (1 - p^2) where ``inside``, lambda = 1 and k = k_fab elsewhere, for
    k = k_r, k_theta, w_b and the compressive ratio c (c_emb, c_fab), to which the numerical
    ``compression_floor`` is added. Shared by the grid and the shell reference
    (``fem_reference.shell``)."""
    p2 = fill ** 2

    def piecewise(emb: float, fab: float) -> np.ndarray:
        return np.where(inside, emb * p2 + fab * (1.0 - p2), fab)

    return FillMixture(lam=np.where(inside, 1.0 + (material.eta - 1.0) * p2, 1.0),
                       k_r=piecewise(material.k_r_emb, material.k_r_fab),
                       k_theta=piecewise(material.k_theta_emb, material.k_theta_fab),
                       w_b=piecewise(material.w_b_emb, material.w_b_fab),
                       compression=piecewise(material.c_emb, material.c_fab) + material.compression_floor)


def make_grid(patch: Patch, material: Material) -> Grid:
    """Discretize one design with the paper's adaptive spacing."""
    n = material.n_nodes
    n_in = n_inside(patch, material)
    if n_in > n - 10:
        raise InvalidInputError(
            f"diameter_mm: {patch.diameter_mm:g} needs {n_in} nodes inside the patch, "
            f"but n_nodes is {n}; increase n_nodes or dr_max_mm")
    dr_mm = patch.diameter_mm / (2.0 * material.eta) / n_in
    mix = fill_mixture(np.arange(n - 1) < n_in, patch.fill, material)
    return Grid(
        n_nodes=n,
        n_inside=n_in,
        dr_mm=dr_mm,
        lam=_ro(mix.lam),
        k_r=_ro(mix.k_r),
        k_theta=_ro(mix.k_theta),
        w_b=_ro(mix.w_b[:-1]),
        w_log=material.w_log,
        gamma=material.gamma_mm / dr_mm,
        compression=_ro(mix.compression),
        jam=material.jam,
        c_jam=material.c_jam,
        bending_scale=(BENDING_REFERENCE_MM / dr_mm) ** 2,
    )
