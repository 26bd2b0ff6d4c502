"""One patch's surface: its profile blended into the flat fabric, revolved, placed on the garment.

Coordinates. The model's profile gives, for every node at rest radius R (relaxed fabric, mm),
its deformed radius r and height z (mm). Garment coordinates are those of the relaxed fabric, so
a node at rest radius R and angle t around a patch centre c is drawn at
``c + r (cos t, sin t)`` with height z: far from the patch r -> R and z -> 0, i.e. the fabric is
where the pattern says. The embroidery boundary is at R_b = d / (2 eta) (d on the pre-stretched
fabric); it sits at r_a after release.

Blend. The model's fabric is an infinite sheet whose height decays slowly (z is still ~7 % of h
at 2.5 R_b for d = 40 mm, p = 0.8). The preview keeps the profile unchanged out to
``R_1 = max(BLEND_START * R_b, R at keypoint b + one node)``, so the dome, a and b are exactly the
model's, and fades it into the flat fabric up to the rim ``R_rim`` with the C1 smoothstep
``w = 3 s^2 - 2 s^3``, ``s = (R - R_1) / (R_rim - R_1)``:

    z_shown = (1 - w) z,    r_shown = (1 - w) r + w R.

At the rim z_shown = 0 and r_shown = R_rim exactly, so the surface meets the flat piece, whose
hole is the circle of radius R_rim sampled at the same angles. ``R_rim = RIM * R_b`` unless
neighbours are closer: a pair of patches at distance D shares it in proportion to their R_b, so
rims never overlap; the rim is never smaller than ``R_1 + MIN_BLEND * R_b`` (patches closer than
that overlap, which the constraint check reports as a spacing violation).

States. "up" is the model's profile; "down" is its mirror image z -> -z. The reduced model is
invariant under that reflection (its energy depends on lengths and on the magnitude of the
hinge angles), so the mirrored profile is its other equilibrium; the real textile differs by
which side the embroidery is on, which the model does not represent.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from stitchswitch.errors import InvalidInputError
from stitchswitch.files.revolution import surface_of_revolution
from stitchswitch.preview3d.profiles import PatchProfile

BLEND_START = 1.25
RIM = 2.0
MIN_BLEND = 0.25
N_THETA = 64


@dataclass(frozen=True, eq=False)
class PatchSurface:
    """A placed patch: triangle mesh (garment mm), the rest radius of every point (mm), its rim
    and the blend start radius (mm)."""

    points: np.ndarray
    triangles: np.ndarray
    rest_radius_mm: np.ndarray
    centre_mm: tuple[float, float]
    rim_radius_mm: float
    blend_start_mm: float
    state: str


def blend_start_mm(profile: PatchProfile) -> float:
    R = profile.R_mm
    b = min(profile.keypoints.b_index + 1, R.size - 1)
    return float(max(BLEND_START * profile.boundary_radius_mm, R[b]))


def rim_radii_mm(centres_mm: np.ndarray, profiles: list[PatchProfile]) -> np.ndarray:
    """Rim radius of every patch: RIM * R_b, shared with closer neighbours (module docstring)."""
    c = np.asarray(centres_mm, dtype=float).reshape(-1, 2)
    rb = np.array([p.boundary_radius_mm for p in profiles])
    rim = RIM * rb
    if len(profiles) > 1:
        dist = np.hypot(*(c[:, None, :] - c[None, :, :]).transpose(2, 0, 1))
        np.fill_diagonal(dist, np.inf)
        share = dist * rb[:, None] / (rb[:, None] + rb[None, :])
        rim = np.minimum(rim, share.min(axis=1))
    floor = np.array([blend_start_mm(p) for p in profiles]) + MIN_BLEND * rb
    return np.maximum(rim, floor)


def shown_profile(profile: PatchProfile, rim_radius_mm: float):
    """(R, r, z) of the drawn profile: nodes inside the rim plus the rim node, blended."""
    R, r, z = profile.R_mm, profile.r_mm, profile.z_mm
    r1 = blend_start_mm(profile)
    if not r1 < rim_radius_mm <= R[-1]:
        raise InvalidInputError(
            f"rim_radius_mm: {rim_radius_mm:g} must lie in ({r1:g}, {R[-1]:g}] mm")
    keep = R < rim_radius_mm
    Rs = np.append(R[keep], rim_radius_mm)
    rs = np.append(r[keep], np.interp(rim_radius_mm, R, r))
    zs = np.append(z[keep], np.interp(rim_radius_mm, R, z))
    s = np.clip((Rs - r1) / (rim_radius_mm - r1), 0.0, 1.0)
    w = s * s * (3.0 - 2.0 * s)
    return Rs, (1.0 - w) * rs + w * Rs, (1.0 - w) * zs


def patch_surface(profile: PatchProfile, centre_mm, state: str = "up",
                  rim_radius_mm: float | None = None, n_theta: int = N_THETA) -> PatchSurface:
    """The patch's blended surface of revolution, centred at ``centre_mm``, popped up or down."""
    if state not in ("up", "down"):
        raise InvalidInputError(f"state: {state!r} must be 'up' or 'down'")
    rim = RIM * profile.boundary_radius_mm if rim_radius_mm is None else float(rim_radius_mm)
    R, r, z = shown_profile(profile, rim)
    points, tris = surface_of_revolution(r, -z if state == "down" else z, n_theta)
    cx, cy = (float(v) for v in centre_mm)
    points[:, 0] += cx
    points[:, 1] += cy
    rest = np.concatenate([[0.0], np.repeat(R[1:], n_theta)])
    return PatchSurface(points, tris, rest, (cx, cy), rim, blend_start_mm(profile), state)


def rim_polygon(centre_mm, rim_radius_mm: float, n_theta: int = N_THETA) -> np.ndarray:
    """The rim circle at the angles ``surface_of_revolution`` uses, (n_theta, 2) garment mm."""
    t = 2 * np.pi * np.arange(n_theta) / n_theta
    return np.column_stack([rim_radius_mm * np.cos(t) + centre_mm[0],
                            rim_radius_mm * np.sin(t) + centre_mm[1]])


def boundary_line(profile: PatchProfile, centre_mm, state: str, eta: float,
                  outline_mm: np.ndarray | None = None, step_mm: float = 1.0) -> np.ndarray:
    """The embroidery's outer boundary drawn on the surface, (n, 3) garment mm, closed.

    The circle R = R_b, or ``outline_mm`` (stretched fabric, relative to the centre): a point at
    stretched radius rho lies at rest radius rho / eta and follows the profile there."""
    if outline_mm is None:
        n = max(32, int(math.ceil(2 * math.pi * profile.boundary_radius_mm / step_mm)))
        t = 2 * np.pi * np.arange(n) / n
        rest = np.full(n, profile.boundary_radius_mm)
    else:
        ring = np.asarray(outline_mm, dtype=float)
        ring = np.vstack([ring, ring[:1]])
        pts = []
        for a, b in zip(ring[:-1], ring[1:]):
            k = max(1, int(math.ceil(np.hypot(*(b - a)) / step_mm)))
            pts.append(a + (b - a) * (np.arange(k) / k)[:, None])
        xy = np.vstack(pts)
        t = np.arctan2(xy[:, 1], xy[:, 0])
        rest = np.hypot(xy[:, 0], xy[:, 1]) / eta
    rest = np.minimum(rest, profile.R_mm[-1])
    r = np.interp(rest, profile.R_mm, profile.r_mm)
    z = np.interp(rest, profile.R_mm, profile.z_mm) * (-1.0 if state == "down" else 1.0)
    line = np.column_stack([centre_mm[0] + r * np.cos(t), centre_mm[1] + r * np.sin(t), z])
    return np.vstack([line, line[:1]])
