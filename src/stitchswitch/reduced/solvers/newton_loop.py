"""The iterations of the certified projected Newton method (``newton``) in one function.

``iterate`` runs Newton from an admissible state until the certificate is met, the budget is
spent or the line search fails: derivatives, certificate and active set, restriction,
shifted bordered-band factorization (``step``, ``bordered``), polar retraction (``retraction``) and Armijo backtracking.
It takes the energy as two functions, ``derivatives(r, z, model, grad, hb, want_h)`` (adds
into grad / hb, returns E) and ``energy(r, z, model)``:

* ``fused_iterate`` is ``iterate`` compiled with the fused default energy (``fused``): the
  whole loop runs in numba (about 0.1 ms per iteration while the restricted band is narrow,
  most of it the bending kernel);
* ``iterate.py_func`` (the same source, interpreted) takes any ``assembly.Model``
  (``model_derivatives``, ``model_energy``): custom term tuples.

It returns at a stationary point with the restricted Hessian's factorization status, so
``newton`` decides there (strict minimum, or a saddle to escape from, in Python) and calls it
again. Status codes: ``MINIMUM``, ``SADDLE``, ``BUDGET``, ``LINE_SEARCH_FAILED``, ``STALLED``
(the certificate at its round-off floor, above ``tol``).
"""
from __future__ import annotations

import numpy as np
from numba import njit

from stitchswitch.reduced.model.terms.segment import BANDWIDTH, NO_HESSIAN
from stitchswitch.reduced.solvers import bordered, fused
from stitchswitch.reduced.solvers.retraction import drops, point, polar
from stitchswitch.reduced.solvers.step import direction, reduced_indices, stationarity

ARMIJO = 1e-4
MAX_BACKTRACK = 60
ROUNDOFF = 1e-13         # relative size of energy changes that rounding cannot resolve
#: Newton goes on past the certificate ``tol`` while it still lowers it, down to AIM * tol:
#: as precise as round-off allows (the soft modes of the profile move by residual over
#: curvature), but certified as soon as the certificate is met.
AIM = 1e-2

MINIMUM, SADDLE, BUDGET, LINE_SEARCH_FAILED, STALLED = 0, 1, 2, 3, 4


@njit(cache=True)
def _slope(g, r_new, r, z_new, z):
    """g_r . (r_new - r) + g_z . (z_new - z): the first-order change of the energy."""
    sr, sz = 0.0, 0.0
    for i in range(r.size):
        sr += g[2 * i] * (r_new[i] - r[i])
        sz += g[2 * i + 1] * (z_new[i] - z[i])
    return sr + sz


@njit(cache=True)
def _dot(a, b):
    s = 0.0
    for i in range(a.size):
        s += a[i] * b[i]
    return s


@njit(cache=True)
def _stationary(At, B, C):
    """The status of a stationary point: ``MINIMUM`` if the restricted Hessian is positive
    definite, else ``SADDLE``."""
    return MINIMUM if bordered.factor(At, B, C, 0.0)[5] == 0 else SADDLE


@njit(cache=True)
def escape_system(hb, free):
    """(ab, dof_map): the restricted Hessian of the banded Hessian ``hb`` and the free drops
    ``free`` in the node-by-node numbering (``step.reduced_indices``, LAPACK's band storage),
    which the saddle escape takes; formed only for an escape."""
    dof_map, n_red = reduced_indices(hb.shape[1] // 2, free)
    return bordered.restrict(hb, dof_map, n_red, 0)[0].T, dof_map


@njit(cache=True)
def _leave(r, z, E, residual, it, shift, status, hb, free):
    """``iterate``'s return."""
    return r, z, E, residual, it, shift, status, hb, free


def iterate(r, z, model, tol, max_iter, it, shift, derivatives, energy):
    """Newton iterations from (r, z) (admissible, dR units) with ``it`` iterations already
    spent and the last Hessian ``shift``. Returns (r, z, E, residual, it, shift, status, hb,
    free): the last state, its energy and certificate, the banded Hessian ``hb`` there and the
    free drops (``escape_system`` makes the saddle escape's system of them)."""
    n = r.size
    grad, hb = np.zeros(2 * n), np.zeros((BANDWIDTH + 1, 2 * n))
    g_new, hb_new = np.zeros(2 * n), np.zeros((BANDWIDTH + 1, 2 * n))
    u = drops(z)
    E_new, fresh = 0.0, False
    raised = False              # the last shift search raised its first trial (a failed factor)
    while True:
        if fresh:               # the accepted trial's derivatives (below): already at (r, z)
            grad, g_new, hb, hb_new, E = g_new, grad, hb_new, hb, E_new
        else:
            grad.fill(0.0)
            hb.fill(0.0)
            E = derivatives(r, z, model, grad, hb, True)
        fresh = False
        residual, free = stationarity(grad, u)
        dof_map, n_band, m = bordered.indices(n, free)
        At, B, C = bordered.restrict(hb, dof_map, n_band, m)
        certified = residual <= tol
        # a stationary point: the certificate met well below tol (AIM), or met and nothing
        # more to gain (the budget spent; below, the round-off floor or a failed search)
        if residual <= AIM * tol or (certified and it >= max_iter):
            return _leave(r, z, E, residual, it, shift, _stationary(At, B, C), hb, free)
        if it >= max_iter:
            return _leave(r, z, E, residual, it, shift, BUDGET, hb, free)
        it += 1
        d, shift, raised = direction(At, B, C, grad, dof_map, shift, raised)
        l, phi, dl, dphi = polar(r, z, d)
        alpha, accepted = 1.0, False
        r_new, z_new = r, z
        if -_dot(grad, d) <= ROUNDOFF * abs(E):
            # The predicted decrease is below the energy's rounding error, so the Armijo test
            # cannot decide: accept the full step if it lowers the certificate instead, and
            # stop if it does not (the certificate is at its round-off floor, where further
            # steps only move the state by ulps). The trial's Hessian is formed with its
            # gradient, so an accepted trial starts the next iteration without a second call.
            ok, r_new, z_new = point(l, phi, dl, dphi, 1.0)
            if ok:
                g_new.fill(0.0)
                hb_new.fill(0.0)
                E_new = derivatives(r_new, z_new, model, g_new, hb_new, True)
                accepted = fresh = stationarity(g_new, drops(z_new))[0] < residual
            if not accepted:
                return _leave(r, z, E, residual, it, shift,
                              _stationary(At, B, C) if certified else STALLED, hb, free)
        for _ in range(0 if accepted else MAX_BACKTRACK):
            ok, r_new, z_new = point(l, phi, dl, dphi, alpha)
            if ok and energy(r_new, z_new, model) <= E + ARMIJO * _slope(grad, r_new, r, z_new, z):
                accepted = True
                break
            alpha *= 0.5
        if not accepted:
            return _leave(r, z, E, residual, it, shift,
                          _stationary(At, B, C) if certified else LINE_SEARCH_FAILED, hb, free)
        r, z = r_new, z_new
        u = drops(z)


@njit(cache=True)
def fused_iterate(r, z, coefficients, tol, max_iter, it, shift):
    """``iterate`` with the fused default energy; ``coefficients`` from ``fused.coefficients``."""
    return _iterate(r, z, coefficients, tol, max_iter, it, shift, fused.derivatives, fused.energy)


_iterate = njit(cache=True)(iterate)


def model_derivatives(r, z, model, grad, hb, want_h):
    """``iterate``'s derivatives for an ``assembly.Model``."""
    return model.accumulate(r, z, grad, hb if want_h else NO_HESSIAN)


def model_energy(r, z, model):
    """``iterate``'s energy for an ``assembly.Model``."""
    return model.energy(r, z)
