"""The measurable quantities of a profile (the paper's Fig. 2): h, (r_a, z_a), (r_b, z_b).

The paper measures "the peak height h; the radial and vertical coordinates (r_a, z_a) at the
embroidery boundary; and the coordinates (r_b, z_b) of the point of minimum radial displacement
just outside the boundary, which marks the transition from the buckled dome to the flat outer
fabric". On the reduced model's nodes (rest radius R_i, deformed radius r_i, height z_i,
z non-increasing in i, gauge z_{N-1} = 0, node ``n_inside`` on the boundary) we define:

1. ``h = z_0 - z_{N-1}``. z is non-increasing, so this is max z minus the far-field level.
   Differences of z only, so h does not depend on the gauge.
2. ``a`` is node ``n_inside``: ``r_a = r[n_inside]``, ``z_a = z[n_inside]``.
3. ``b``:

   * If ``h < FLAT_H_MM`` there is no dome and no transition: ``b = a``, rule ``"flat"``.
   * Otherwise the search window W runs from ``n_inside`` to the *foot*, the first node
     i >= n_inside with ``z_i - z_{N-1} <= FOOT_FRACTION * h`` (the dome has reached the flat
     fabric; beyond it r ~ R and "minimum radial displacement" would pick far-field noise).
     If the foot is ``n_inside`` itself, W is ``n_inside, n_inside + 1``.
     Let ``s = dr/dR`` (centered differences, one-sided at the array ends).
   * If ``min_W s > 0`` the profile never turns inward (no overhang): b is the node of W with
     the smallest s, rule ``"steepest"``: where the profile is most vertical, i.e. makes the
     least outward radial progress.
   * Otherwise the profile overhangs (a "mushroom": r decreases past the boundary and then
     increases again): b is the first local minimum of r in W at or after the first node of
     W with ``s <= 0``, rule ``"neck"``. If r keeps decreasing to the end of W, b is the node
     of minimum r in W.

   Ties go to the first index. The two non-flat rules join continuously: as an overhang
   appears, the neck is born at the point of zero slope, which is the point of minimum
   slope, so b does not jump when the rule switches.

All values are in mm, returned as plain Python floats (and ``b_index`` as an int).
"""
from __future__ import annotations

import operator
from dataclasses import dataclass

import numpy as np

from stitchswitch.errors import InvalidInputError

#: Peak height (mm) below which a profile counts as flat: b is then the boundary node a.
FLAT_H_MM = 0.01
#: The dome's foot is the first node at or past the boundary whose height above the far
#: field is at most this fraction of h; it closes the window searched for b.
FOOT_FRACTION = 0.01


@dataclass(frozen=True)
class Keypoints:
    """h, a = (r_a, z_a), b = (r_b, z_b) in mm; ``b_index`` is b's node, ``b_rule`` how it
    was chosen ("neck", "steepest" or "flat"). See the module docstring."""

    h_mm: float
    r_a_mm: float
    z_a_mm: float
    r_b_mm: float
    z_b_mm: float
    b_index: int
    b_rule: str


def _as_profile(name: str, values) -> np.ndarray:
    a = np.asarray(values, dtype=float)
    if a.ndim != 1:
        raise InvalidInputError(f"{name}: must be a 1D array, got shape {a.shape}")
    if not np.isfinite(a).all():
        bad = np.flatnonzero(~np.isfinite(a))
        raise InvalidInputError(f"{name}: non-finite value {float(a[bad[0]])!r} at index {bad[0]}")
    return a


def _validate(R_mm, r_mm, z_mm, n_inside):
    R, r, z = (_as_profile(n, v) for n, v in (("R_mm", R_mm), ("r_mm", r_mm), ("z_mm", z_mm)))
    if not (R.size == r.size == z.size):
        raise InvalidInputError(
            f"R_mm, r_mm, z_mm: lengths {R.size}, {r.size}, {z.size} must be equal")
    if isinstance(n_inside, bool):
        raise InvalidInputError(f"n_inside: {n_inside!r} is not an integer")
    try:
        n = operator.index(n_inside)
    except TypeError:
        raise InvalidInputError(f"n_inside: {n_inside!r} is not an integer") from None
    if not 0 < n < R.size - 1:
        raise InvalidInputError(f"n_inside: {n} must satisfy 0 < n_inside < N - 1 = {R.size - 1}")
    steps = np.diff(R)
    if not (steps > 0).all():
        i = int(np.argmax(steps <= 0))
        raise InvalidInputError(f"R_mm: must be strictly increasing, got {float(R[i])!r} "
                                f"then {float(R[i + 1])!r} at index {i + 1}")
    return R, r, z, n, steps


def _slopes(r, steps, lo: int, hi: int) -> np.ndarray:
    """``np.gradient(r, R)[lo:hi + 1]`` (``steps`` = diff(R)) computed on the window alone, by
    numpy's own formulas (second-order centred inside, one-sided at the ends, the uniform-step
    form when every step is equal), so the numbers are numpy's bit for bit."""
    n = r.size
    out = np.empty(hi + 1 - lo)
    uniform = bool((steps == steps[0]).all())
    a, b = max(lo, 1), min(hi, n - 2)
    if a <= b:
        if uniform:
            out[a - lo:b + 1 - lo] = (r[a + 1:b + 2] - r[a - 1:b]) / (2. * steps[0])
        else:
            dx1, dx2 = steps[a - 1:b], steps[a:b + 1]
            out[a - lo:b + 1 - lo] = (-(dx2) / (dx1 * (dx1 + dx2)) * r[a - 1:b]
                                      + (dx2 - dx1) / (dx1 * dx2) * r[a:b + 1]
                                      + dx1 / (dx2 * (dx1 + dx2)) * r[a + 1:b + 2])
    if lo == 0:
        out[0] = (r[1] - r[0]) / steps[0]
    if hi == n - 1:
        out[-1] = (r[-1] - r[-2]) / steps[-1]
    return out


def _b_node(r, z, n_inside, h, steps) -> tuple[int, str]:
    if h < FLAT_H_MM:
        return n_inside, "flat"
    above = z[n_inside:] - z[-1]
    foot = n_inside + int(np.argmax(above <= FOOT_FRACTION * h))  # exists: above[-1] == 0
    lo, hi = n_inside, max(foot, n_inside + 1)
    s = _slopes(r, steps, lo, hi)
    if s.min() > 0:
        return lo + int(np.argmin(s)), "steepest"
    k0 = lo + int(np.argmax(s <= 0))
    rises = np.flatnonzero(np.diff(r[k0:hi + 1]) > 0)
    if rises.size == 0:
        return lo + int(np.argmin(r[lo:hi + 1])), "neck"
    end = k0 + int(rises[0])  # r is non-increasing on k0..end and rises after end
    return k0 + int(np.argmin(r[k0:end + 1])), "neck"


def keypoints_from_profile(R_mm, r_mm, z_mm, n_inside) -> Keypoints:
    """Keypoints of the profile (R_i, r_i, z_i), i = 0..N-1, with node ``n_inside`` on the
    embroidery boundary. Raises InvalidInputError on mismatched lengths, non-finite values,
    a non-increasing R or ``n_inside`` outside 1..N-2."""
    R, r, z, n, steps = _validate(R_mm, r_mm, z_mm, n_inside)
    h = float(z[0] - z[-1])
    b, rule = _b_node(r, z, n, h, steps)
    return Keypoints(h_mm=h, r_a_mm=float(r[n]), z_a_mm=float(z[n]),
                     r_b_mm=float(r[b]), z_b_mm=float(z[b]), b_index=int(b), b_rule=rule)


def keypoints(solution) -> Keypoints:
    """Keypoints of anything with ``R_mm, r_mm, z_mm`` and ``n_inside`` (e.g. a Solution)."""
    return keypoints_from_profile(solution.R_mm, solution.r_mm, solution.z_mm, solution.n_inside)
