"""Keypoints (h, a, b) on analytically constructed profiles."""
from __future__ import annotations

import dataclasses
import math
from types import SimpleNamespace

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.optimize import brentq
from scipy.special import erf

from stitchswitch.errors import InvalidInputError
from stitchswitch.reduced.model.keypoints import (
    FLAT_H_MM,
    FOOT_FRACTION,
    Keypoints,
    keypoints,
    keypoints_from_profile,
)

N, DR, N_IN = 300, 0.5, 40
R = np.arange(N) * DR
R_MAX = R[-1]
H, LZ = 5.0, 30.0          # dome height and width (mm): z = H exp(-(R/LZ)^2) - far-field level
L = 20.0                   # width of the radial displacement of the mushroom family
A_CRIT = math.exp(1.5) / 2  # r = R (1 + A exp(-(R/L)^2)) overhangs iff A > A_CRIT


def dome_z(height=H, width=LZ):
    return height * np.exp(-(R / width) ** 2) - height * math.exp(-(R_MAX / width) ** 2)


def mushroom_r(A):
    """dr/dR = 1 + A exp(-x^2) (1 - 2 x^2), x = R / L: its minimum 1 - 2 A e^{-1.5} is at
    x = sqrt(1.5) and is negative (an overhang) iff A > A_CRIT. r -> R far away."""
    return R * (1 + A * np.exp(-(R / L) ** 2))


def test_steepest_smooth_dome():
    # dr/dR = 1 - c exp(-((R - R0)/w)^2) > 0: r strictly increasing, slope smallest at R0.
    c, R0, w = 0.8, 30.0, 5.0
    r = R - c * w * math.sqrt(math.pi) / 2 * (erf((R - R0) / w) + erf(R0 / w))
    z = dome_z()
    assert r[0] == 0 and np.all(np.diff(r) > 0)

    kp = keypoints_from_profile(R, r, z, N_IN)

    assert kp.b_rule == "steepest"
    assert kp.b_index == 60  # R0 / DR; the bump is symmetric about node 60
    assert kp.r_b_mm == r[60] and kp.z_b_mm == z[60]
    assert kp.h_mm == pytest.approx(H * (1 - math.exp(-(R_MAX / LZ) ** 2)), abs=1e-12)
    assert kp.r_a_mm == r[N_IN] and kp.z_a_mm == z[N_IN]
    assert kp.z_a_mm == pytest.approx(H * math.exp(-(20.0 / LZ) ** 2), abs=1e-9)
    assert kp.r_a_mm == pytest.approx(
        20.0 - c * w * math.sqrt(math.pi) / 2 * (erf(-2.0) + erf(6.0)), abs=1e-12)


def test_neck_of_mushroom():
    A = 2 * A_CRIT
    r, z = mushroom_r(A), dome_z()
    slope = lambda x: 1 + A * math.exp(-x * x) * (1 - 2 * x * x)  # noqa: E731
    assert slope(20.0 / L) < 0  # r already decreasing at the boundary
    R_neck = L * brentq(slope, math.sqrt(1.5), 3.0)  # where r stops decreasing

    kp = keypoints_from_profile(R, r, z, N_IN)

    assert kp.b_rule == "neck"
    assert kp.b_index == N_IN + int(np.argmin(r[N_IN:100]))
    assert abs(R[kp.b_index] - R_neck) <= DR
    b = kp.b_index
    assert r[b - 1] > r[b] < r[b + 1]
    assert kp.r_b_mm == r[b] and kp.z_b_mm == z[b]
    assert kp.r_b_mm < kp.r_a_mm and kp.z_b_mm < kp.z_a_mm
    assert kp.r_a_mm == pytest.approx(20.0 * (1 + A * math.exp(-1.0)), abs=1e-12)


@pytest.mark.parametrize("height", [0.0, FLAT_H_MM / 2])
def test_flat_profile(height):
    z = np.zeros(N) if height == 0 else dome_z(height)
    kp = keypoints_from_profile(R, R.copy(), z, N_IN)
    assert kp.b_rule == "flat"
    assert kp.h_mm == pytest.approx(height, abs=1e-12)
    assert kp.b_index == N_IN
    assert (kp.r_b_mm, kp.z_b_mm) == (kp.r_a_mm, kp.z_a_mm) == (R[N_IN], z[N_IN])


def test_b_continuous_as_overhang_appears():
    z = dome_z()
    no_overhang = keypoints_from_profile(R, mushroom_r(0.999 * A_CRIT), z, N_IN)
    tiny_overhang = keypoints_from_profile(R, mushroom_r(1.003 * A_CRIT), z, N_IN)
    assert no_overhang.b_rule == "steepest" and tiny_overhang.b_rule == "neck"
    # Both sit at the inflection x = sqrt(1.5) of the critical profile.
    node_crit = L * math.sqrt(1.5) / DR
    assert abs(no_overhang.b_index - node_crit) <= 1
    assert abs(tiny_overhang.b_index - no_overhang.b_index) <= 2
    assert abs(tiny_overhang.r_b_mm - no_overhang.r_b_mm) < 0.1
    assert abs(tiny_overhang.z_b_mm - no_overhang.z_b_mm) < 0.1


def test_dome_inside_patch_uses_two_node_window():
    # The dome has already reached the flat fabric at the boundary (foot == n_inside):
    # W = {n_inside, n_inside + 1}; with r = R the slopes tie and the first index wins.
    z = dome_z(width=5.0)
    assert z[N_IN] - z[-1] <= FOOT_FRACTION * (z[0] - z[-1])
    kp = keypoints_from_profile(R, R.copy(), z, N_IN)
    assert (kp.b_rule, kp.b_index) == ("steepest", N_IN)


def test_gauge_invariance():
    r, z = mushroom_r(2 * A_CRIT), dome_z()
    kp0 = keypoints_from_profile(R, r, z, N_IN)
    kp1 = keypoints_from_profile(R, r, z + 7.25, N_IN)
    assert kp1.h_mm == pytest.approx(kp0.h_mm, abs=1e-12)
    assert (kp1.b_index, kp1.b_rule) == (kp0.b_index, kp0.b_rule)
    assert (kp1.r_a_mm, kp1.r_b_mm) == (kp0.r_a_mm, kp0.r_b_mm)
    assert kp1.z_a_mm - (z[-1] + 7.25) == pytest.approx(kp0.z_a_mm - z[-1], abs=1e-12)
    assert kp1.z_b_mm - (z[-1] + 7.25) == pytest.approx(kp0.z_b_mm - z[-1], abs=1e-12)


def test_keypoints_from_solution_like_object_returns_plain_types():
    r, z = mushroom_r(2 * A_CRIT), dome_z()
    sol = SimpleNamespace(R_mm=R, r_mm=r, z_mm=z, n_inside=np.int64(N_IN))
    kp = keypoints(sol)
    assert kp == keypoints_from_profile(R, r, z, N_IN)
    for f in ("h_mm", "r_a_mm", "z_a_mm", "r_b_mm", "z_b_mm"):
        assert type(getattr(kp, f)) is float
    assert type(kp.b_index) is int and type(kp.b_rule) is str
    with pytest.raises(dataclasses.FrozenInstanceError):
        kp.h_mm = 0.0
    assert isinstance(kp, Keypoints)


def _with_nan(a, i):
    a = a.copy()
    a[i] = np.nan
    return a


@pytest.mark.parametrize("args, match", [
    ((R, R, R[:-1], N_IN), r"z_mm.*299"),
    ((R, R[:10], R, N_IN), r"r_mm.*10"),
    ((R, R, R, 0), r"n_inside: 0"),
    ((R, R, R, N - 1), r"n_inside: 299"),
    ((R, R, R, N), r"n_inside: 300"),
    ((R, R, R, -3), r"n_inside: -3"),
    ((R, R, R, 40.5), r"n_inside: 40\.5"),
    ((R, R, R, True), r"n_inside: True"),
    ((R, _with_nan(R, 7), R, N_IN), r"r_mm: non-finite value nan at index 7"),
    ((R, R, np.where(R == R[5], np.inf, R), N_IN), r"z_mm: non-finite value inf at index 5"),
    ((_with_nan(R, 3), R, R, N_IN), r"R_mm: non-finite"),
    ((R[::-1], R, R, N_IN), r"R_mm: must be strictly increasing"),
    ((R[None, :], R, R, N_IN), r"R_mm: must be a 1D array"),
])
def test_invalid_inputs(args, match):
    with pytest.raises(InvalidInputError, match=match):
        keypoints_from_profile(*args)


@given(st.integers(3, 40), st.booleans(), st.integers(0, 2**32 - 1), st.data())
@settings(max_examples=300, deadline=None)
def test_window_slopes_are_numpys_gradient_bit_for_bit(n, uniform, seed, data):
    """b's window takes dr/dR on the window alone; it must be np.gradient's numbers exactly
    (argmin and sign tests on them pick b), on even and uneven steps and windows that reach
    either end of the profile."""
    from stitchswitch.reduced.model.keypoints import _slopes

    rng = np.random.default_rng(seed)
    R_ = np.arange(n) * 0.37 if uniform else np.cumsum(rng.uniform(0.05, 1.0, n))
    r = R_ + rng.normal(0.0, 0.3, n)
    lo = data.draw(st.integers(0, n - 1))
    hi = data.draw(st.integers(lo, n - 1))
    assert _slopes(r, np.diff(R_), lo, hi).tobytes() == np.gradient(r, R_)[lo:hi + 1].tobytes()
