"""The energy compiled as one function: the kernels of ``terms.ALL_TERMS`` called in a fixed
order, then those of the added terms of ``EXTRAS`` that are present, so the Newton loop
(``newton_loop``) evaluates the energy, gradient and banded Hessian without returning to Python.

``coefficients(terms, grid)`` decides whether a term tuple can take this path: its first terms
must have the default terms' kernels in the default order (their ``energy`` and ``accumulate``
are the very same functions, as for every ``dataclasses.replace`` variant such as
``terms.variants`` or a grid transform of the discovery effects); only the coefficients may
differ. After them may come added terms (``EXTRAS``: a second hardening term, natural curvature,
hoop bending, gravity: the energies the discovery effects add), each at most once and in that
order.
It returns the coefficients as a tuple per default term and one tuple for the added terms (an
absent one has empty arrays), or None for any other tuple, which the solver evaluates through
``assembly.Model`` instead (about three times slower per Newton iteration). Each kernel is
called with the same arguments as ``Term.energy``/``Term.accumulate`` and the terms are summed
in the same order, so both paths give the same numbers (tests/test_fused.py).

numba's on-disk cache of these functions does not notice an edit of a kernel module they call;
``reduced.model.kernel_cache`` clears the cache whenever a kernel source changes (and
tests/test_fused.py would fail on a stale one, because the Python path recompiles the kernel).
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit

from stitchswitch.reduced.model.terms import (
    ALL_TERMS,
    bending,
    boundary_ring,
    circumferential,
    compression,
    hardening,
    radial,
)
from stitchswitch.reduced.model.terms.extra import gravity, hoop_bending, natural_curvature
from stitchswitch.reduced.model.terms.hinge import HESS_DOT, HESS_X
from stitchswitch.reduced.model.terms.segment import BANDWIDTH, add_segment, segment, segment_lengths

#: Array dimensions (-1: a scalar, "index": a 1-d integer array) of each default term's
#: coefficients, in assembly order.
LAYOUT = ((1, 1), (1, 1, 1, 1), (1, 1), (1, -1, -1), ("index", 1, 1, 1, -1), (1,))
#: The added terms the compiled energy evaluates after the default ones, in this order (a
#: second hardening, natural curvature, hoop bending, gravity): (energy, accumulate) of each
#: kind. A term is of a kind when its ``energy`` and ``accumulate`` are these very functions,
#: whatever its coefficients (``hardening.with_weight`` is a second hardening term).
#: ``EXTRA_LAYOUT``: the dimensions of their coefficients.
EXTRAS = ((hardening.TERM.energy, hardening.TERM.accumulate),
          (natural_curvature.energy, natural_curvature.accumulate),
          (hoop_bending.energy, hoop_bending.accumulate),
          (gravity.energy, gravity.accumulate))
EXTRA_LAYOUT = ((1, -1, -1), (1, 1), (1,), (1,))


def _prepared(value, ndim):
    """A coefficient as the compiled functions take it, or None if it has another shape:
    ``_converted``'s result, with its two common cases (a contiguous float array, returned as
    it is, and a Python float) answered without numpy's conversion."""
    if (type(value) is np.ndarray and value.ndim and value.dtype == np.float64
            and value.flags.c_contiguous):
        return value if ndim == value.ndim else None
    if type(value) is float and ndim == -1:
        return value
    return _converted(value, ndim)


def _converted(value, ndim):
    """The general rule: ``value`` converted by numpy for ``ndim`` ("index": a 1-d integer
    array; -1: a scalar; else a float array of that many dimensions), or None."""
    if ndim == "index":
        a = np.ascontiguousarray(value)
        return a.astype(np.int64) if a.ndim == 1 and a.dtype.kind in "iu" else None
    if ndim < 0:
        return float(value) if np.ndim(value) == 0 else None
    a = np.ascontiguousarray(value, dtype=float)
    return a if a.ndim == ndim else None


def _extra_kind(term) -> int | None:
    """The index in ``EXTRAS`` of the kind whose kernels ``term`` has, or None."""
    for k, (energy_fn, accumulate_fn) in enumerate(EXTRAS):
        if term.energy is energy_fn and term.accumulate is accumulate_fn:
            return k
    return None


def _coefficients(term, grid, layout):
    coef = tuple(term.coefficients(grid))
    if len(coef) != len(layout):
        return None
    coef = tuple(_prepared(v, k) for v, k in zip(coef, layout))
    return None if any(v is None for v in coef) else coef


def coefficients(terms, grid):
    """The per-term coefficient tuples of ``terms`` on ``grid``, then those of the added terms,
    if ``terms`` are the default kernels in the default order followed by ``EXTRAS`` terms
    (see the module docstring), else None."""
    terms = tuple(terms)
    n = len(ALL_TERMS)
    if len(terms) < n or any(t.energy is not d.energy or t.accumulate is not d.accumulate
                             for t, d in zip(terms, ALL_TERMS)):
        return None
    kinds = [_extra_kind(t) for t in terms[n:]]
    if None in kinds or kinds != sorted(set(kinds)):
        return None
    out = []
    for term, layout in zip(terms, LAYOUT):
        coef = _coefficients(term, grid, layout)
        if coef is None:
            return None
        out.append(coef)
    # an absent term: empty arrays (and zero scalars), which the compiled energy skips
    extras = [tuple(np.zeros(0) if k == 1 else 0.0 for k in layout) for layout in EXTRA_LAYOUT]
    for term, k in zip(terms[n:], kinds):
        coef = _coefficients(term, grid, EXTRA_LAYOUT[k])
        if coef is None:
            return None
        extras[k] = coef
    return tuple(out) + (tuple(extras),)


@njit(cache=True)
def in_domain(r, z):
    """``assembly.in_domain``: finite coordinates and r_i > 0 for i >= 1."""
    for i in range(r.size):
        if not (math.isfinite(r[i]) and math.isfinite(z[i])):
            return False
        if i > 0 and not r[i] > 0.0:
            return False
    return True


@njit(cache=True)
def _same(a, b):
    """True if the two arrays hold the same values."""
    if a.size != b.size:
        return False
    for i in range(a.size):
        if not a[i] == b[i]:
            return False
    return True


@njit(cache=True)
def _membrane(r, z, cr, cc, lengths, grad, hb, want_g, want_h):
    """(E_radial, E_compression): ``radial._kernel`` with coefficients ``cr`` and
    ``compression._kernel`` with ``cc`` in one loop over the segments, each segment's length
    computed once and written into ``lengths`` (for the bending term).

    Both kernels add into the same entries (a segment's dofs), so the loop may interleave them
    only where that cannot change a sum: with one rest length for both (the default terms and
    their variants), a segment is stretched (radial) or slack (compression), never both, so
    every entry of grad and hb receives at most two additions here (from the segments on either
    side of a node), starting from zero, and two additions commute. The energies are summed
    apart, each in segment order, and compression stops at a segment of zero length as its
    kernel does (+inf). With other rest lengths the kernels run one after the other."""
    lam, w = cr[0], cr[1]
    lam_c, wc, jammed, wj = cc[0], cc[1], cc[2], cc[3]
    if not _same(lam, lam_c):
        lengths[:] = segment_lengths(r, z)
        return (radial._kernel(r, z, lam, w, grad, hb, want_g, want_h),
                compression._kernel(r, z, lam_c, wc, jammed, wj, grad, hb, want_g, want_h))
    Er, Ec = 0.0, 0.0
    live = True                            # compression has met no segment of zero length
    for i in range(r.size - 1):
        vr, vz, l = segment(r, z, i)
        lengths[i] = l
        active, e, d1, d2 = radial.stretched(l, lam[i], w[i])
        if active:                         # l > lambda, so l / lambda >= 1: not slack
            Er += e
            if want_g:
                add_segment(grad, hb, i, d1, d2, vr, vz, l, want_h)
            continue
        if not live:
            continue
        if l <= 0.0:
            Ec, live = math.inf, False
            continue
        active, jam, e, e_jam, d1, d2 = compression.slack(l, lam_c[i], wc[i], jammed[i], wj[i])
        if not active:
            continue
        Ec += e
        if jam:
            Ec += e_jam
        if want_g:
            add_segment(grad, hb, i, d1, d2, vr, vz, l, want_h)
    return Er, Ec


@njit(cache=True)
def _added(total, r, z, x, grad, hb, want_g, want_h):
    """``total`` plus the energies of the added terms present in ``x`` (``coefficients``' last
    tuple, ``EXTRAS`` order), each added in turn as the assembly adds them; their gradient
    (``want_g``) and Hessian (``want_h``) go into ``grad`` and ``hb``."""
    if x[0][0].size:
        total += hardening._kernel(r, z, x[0][0], x[0][1], x[0][2], grad, hb, want_g, want_h)
    if x[1][0].size:
        total += natural_curvature._kernel(r, z, x[1][0], x[1][1], grad, hb, want_g, want_h,
                                           HESS_X, HESS_DOT)
    if x[2][0].size:
        total += hoop_bending._kernel(r, z, x[2][0], grad, hb, want_g, want_h)
    if x[3][0].size:
        total += gravity._kernel(z, x[3][0], grad, want_g)
    return total


@njit(cache=True)
def energy(r, z, c):
    """Total energy (``assembly.Model.energy``); +inf outside the domain."""
    if not in_domain(r, z):
        return math.inf
    no_g, no_h = np.zeros(0), np.zeros((BANDWIDTH + 1, 0))
    total = 0.0
    lengths = np.empty(r.size - 1)
    Er, Ec = _membrane(r, z, c[0], c[1], lengths, no_g, no_h, False, False)
    total += Er
    total += Ec
    total += circumferential._kernel(r, z, c[2][0], c[2][1], no_g, no_h, False, False)
    total += hardening._kernel(r, z, c[3][0], c[3][1], c[3][2], no_g, no_h, False, False)
    total += boundary_ring._kernel(r, z, c[4][0], c[4][1], c[4][2], c[4][3], c[4][4], no_g, no_h,
                                   False, False)
    total += bending.energy_lengths(r, z, c[5][0], lengths)
    total = _added(total, r, z, c[6], no_g, no_h, False, False)
    return total if math.isfinite(total) else math.inf


@njit(cache=True)
def derivatives(r, z, c, grad, hb, want_h):
    """Add the gradient into ``grad`` (2N,) and, if ``want_h``, the banded Hessian into ``hb``
    (6, 2N); return the energy (``assembly.Model.accumulate``)."""
    total = 0.0
    lengths = np.empty(r.size - 1)
    Er, Ec = _membrane(r, z, c[0], c[1], lengths, grad, hb, True, want_h)
    total += Er
    total += Ec
    total += circumferential._kernel(r, z, c[2][0], c[2][1], grad, hb, True, want_h)
    total += hardening._kernel(r, z, c[3][0], c[3][1], c[3][2], grad, hb, True, want_h)
    total += boundary_ring._kernel(r, z, c[4][0], c[4][1], c[4][2], c[4][3], c[4][4], grad, hb, True,
                                   want_h)
    total += bending.kernel_lengths(r, z, c[5][0], lengths, grad, hb, want_h)
    return _added(total, r, z, c[6], grad, hb, True, want_h)
