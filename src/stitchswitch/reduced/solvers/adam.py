"""The paper's own solver, projected Adam with gradient clipping, kept as a baseline.

What the paper does: "the simulation minimizes (6) using Adam with gradient clipping", with
the sign constraint z'(R) <= 0 enforced throughout. The modelling notes record the settings
that were used: learning rate 0.05, gradient clipping at global norm 1.0, 20,000 steps.

What we do (``minimize``):

* The free variables are x = (r_1..r_{N-1}, z_0..z_{N-1}) in dR units (r_0 = 0 is fixed).
* Each step: gradient of the total energy (``assembly.Model.gradient``), clipped to global
  Euclidean norm ``clip``; standard Adam moments m, v with bias correction (``beta1``,
  ``beta2``, ``eps``); step x <- x - lr * m_hat / (sqrt(v_hat) + eps); then the state is
  projected onto the constraint set with ``constraints.project`` (pole r_0 = 0, z_0 = z_1,
  z non-increasing by isotonic regression, gauge z_{N-1} = 0, r_i >= 1e-6).
* Domain safeguard (ours, NOT the paper's): if the projected new state has infinite energy
  (a segment folded or collapsed, or r <= 0), the same step is retried with half the step
  size, up to 30 halvings; if all of them fail the step is rejected (the state is kept, the
  moments keep their update). Everything is deterministic.
* The *final* iterate is returned (not the best one seen), certified exactly as the Newton
  solver certifies its result: the max-norm of the projected gradient of the
  bound-constrained problem (``constraints.kkt_residual``); ``converged`` is True only if
  it is <= ``tol``. ``second_order`` is None (not checked).

Defaults: steps=20000, lr=0.05, clip=1.0, beta1=0.9, beta2=0.999, eps=1e-8.

Why it is only a baseline: Adam with a fixed learning rate does not converge to a
stationary point; it ends oscillating with a step of order lr, so after 20,000 steps the
projected gradient is typically still far from zero (orders of magnitude above the
certificate tolerance), and clipping makes the early phase a slow fixed-length descent.
Its result is reported with its (honest) residual and is not converged in general; use the
certified projected Newton method (``newton``, the default of ``solve``) for results.
"""
from __future__ import annotations

import numbers

import numpy as np

from stitchswitch.errors import InvalidInputError
from stitchswitch.reduced.model import assembly
from stitchswitch.reduced.model.discretization import Grid
from stitchswitch.reduced.solvers.constraints import kkt_residual, project
from stitchswitch.reduced.solvers.newton import NewtonResult

#: Domain safeguard: how many times a step that leaves the energy's domain is halved.
MAX_HALVINGS = 30


def _positive(name: str, value) -> float:
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise InvalidInputError(f"{name}: {value!r} is not a number") from None
    if not (np.isfinite(v) and v > 0):
        raise InvalidInputError(f"{name}: {value!r} must be a positive finite number")
    return v


def _validate(steps, lr, clip, beta1, beta2, eps, tol):
    if isinstance(steps, bool) or not isinstance(steps, numbers.Integral) or steps < 0:
        raise InvalidInputError(f"steps: {steps!r} must be an integer >= 0")
    lr = _positive("lr", lr)
    clip = _positive("clip", clip)
    eps = _positive("eps", eps)
    tol = _positive("tol", tol)
    for name, b in (("beta1", beta1), ("beta2", beta2)):
        try:
            bf = float(b)
        except (TypeError, ValueError):
            raise InvalidInputError(f"{name}: {b!r} is not a number") from None
        if not 0.0 <= bf < 1.0:
            raise InvalidInputError(f"{name}: {b!r} is outside [0, 1)")
    return int(steps), lr, clip, float(beta1), float(beta2), eps, tol


def _certificate(r: np.ndarray, z: np.ndarray, model: assembly.Model) -> float:
    """The Newton solver's certificate: max-norm of the projected gradient."""
    g = model.gradient(r, z)
    return kkt_residual(g[0::2], g[1::2], z[:-1] - z[1:])


def minimize(grid: Grid, r0: np.ndarray, z0: np.ndarray, *, tol: float, steps: int = 20000,
             lr: float = 0.05, clip: float = 1.0, beta1: float = 0.9, beta2: float = 0.999,
             eps: float = 1e-8) -> NewtonResult:
    """Projected Adam with global-norm gradient clipping from (r0, z0), dR units.

    Returns the final iterate with its energy and certificate (see the module docstring);
    ``iterations`` is the number of steps taken."""
    steps, lr, clip, beta1, beta2, eps, tol = _validate(steps, lr, clip, beta1, beta2, eps, tol)
    n = grid.n_nodes
    r, z = project(np.asarray(r0, dtype=float), np.asarray(z0, dtype=float))
    if r.size != n or z.size != n:
        raise InvalidInputError(f"r0, z0: sizes {r.size}, {z.size} do not match n_nodes {n}")
    model = assembly.Model(grid)
    E = model.energy(r, z)
    if not np.isfinite(E):
        return NewtonResult(r, z, float(E), np.inf, 0, False, None,
                            "adam: start is outside the energy's domain")

    m = np.zeros(2 * n - 1)
    v = np.zeros(2 * n - 1)
    rejected = 0
    for t in range(1, steps + 1):
        g = model.gradient(r, z)
        gx = np.concatenate([g[0::2][1:], g[1::2]])
        norm = float(np.linalg.norm(gx))
        if norm > clip:
            gx = gx * (clip / norm)
        m = beta1 * m + (1.0 - beta1) * gx
        v = beta2 * v + (1.0 - beta2) * gx * gx
        m_hat = m / (1.0 - beta1 ** t)
        v_hat = v / (1.0 - beta2 ** t)
        step = lr * m_hat / (np.sqrt(v_hat) + eps)
        for _ in range(MAX_HALVINGS + 1):
            r_try = np.concatenate([[0.0], r[1:] - step[:n - 1]])
            r_new, z_new = project(r_try, z - step[n - 1:])
            E_new = model.energy(r_new, z_new)
            if np.isfinite(E_new):
                r, z, E = r_new, z_new, E_new
                break
            step = 0.5 * step
        else:
            rejected += 1

    residual = _certificate(r, z, model)
    converged = bool(residual <= tol)
    message = (f"adam: {steps} steps, residual {residual:.1e} "
               f"{'<=' if converged else '>'} tol {tol:g} "
               f"({'converged' if converged else 'not converged'})")
    if rejected:
        message += f"; {rejected} step(s) rejected by the domain safeguard"
    return NewtonResult(r, z, float(E), float(residual), steps, converged, None, message)
