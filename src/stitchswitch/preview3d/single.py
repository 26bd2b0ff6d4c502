"""Cross-section figures of one patch (matplotlib): alone, or cut out of a design's scene.

``figure_bytes``: the single-patch figure, the profile, its keypoints and their dimensions.

What a designer checks before stitching: the cross-section of the released patch (the model's
profile, mirrored about the axis), the embroidered part drawn thick, the apex height h, the
boundary point a = (r_a, z_a) dimensioned on the left half and the transition point
b = (r_b, z_b) on the right half, with the flat far-field level z = 0. Horizontal positions are
deformed radii r in mm on the relaxed fabric (garment frame); the caption gives d (pre-stretched),
the relaxed footprint d / eta and the profile's source. "down" mirrors z.
PNG or SVG by extension, written atomically and deterministically.

``section_bytes``: the section view of a design, the scene (``scene.Scene``: pieces and patch
surfaces as previewed, blend included) cut by the vertical plane y = y_c through a patch's
centre (pyvista's ``slice``), over twice the patch's rim radius on each side, so neighbours
within that reach are cut too. The patch is drawn in its colour (red up, blue down), its
embroidered part (rest radius <= R_b) thick, other patches dark grey and the fabric light grey,
with its apex height dimensioned. Heights can be exaggerated (the axes' aspect; the figure says
by how much).
"""
from __future__ import annotations

from stitchswitch.errors import InvalidInputError
from stitchswitch.files.atomic import atomic_write_bytes
from stitchswitch.files.extensions import check_extension
from stitchswitch.files.figures import plot_bytes
from stitchswitch.preview3d.profiles import PatchProfile

FIGURE_FORMATS = (".png", ".svg")
EXTENT = 2.2          # the figure shows rest radii up to EXTENT * R_b


def check_figure_path(path) -> str:
    return check_extension(path, FIGURE_FORMATS)


def _dimension(ax, p, q, text, offset=(0, 0), ha="center", va="center", at=0.5):
    """A double arrow from p to q, labelled at fraction ``at`` of the way."""
    ax.annotate("", xy=q, xytext=p, arrowprops=dict(arrowstyle="<->", lw=0.8, color="0.2",
                                                    shrinkA=0, shrinkB=0))
    mid = (p[0] + at * (q[0] - p[0]), p[1] + at * (q[1] - p[1]))
    ax.annotate(text, xy=mid, xytext=offset, textcoords="offset points", ha=ha, va=va,
                fontsize=8, color="0.1",
                bbox=dict(boxstyle="round,pad=0.15", fc="white", ec="none", alpha=0.85))


def figure_bytes(profile: PatchProfile, fmt: str = "png", state: str = "up",
                 material_name: str = "default", eta: float = 1.7) -> bytes:
    import matplotlib
    matplotlib.use("Agg", force=False)
    import matplotlib.pyplot as plt

    if state not in ("up", "down"):
        raise InvalidInputError(f"state: {state!r} must be 'up' or 'down'")
    sign = -1.0 if state == "down" else 1.0
    kp, n_in = profile.keypoints, profile.n_inside
    keep = profile.R_mm <= EXTENT * profile.boundary_radius_mm
    r, z = profile.r_mm[keep], sign * profile.z_mm[keep]
    h, ra, za, rb, zb = kp.h_mm, kp.r_a_mm, sign * kp.z_a_mm, kp.r_b_mm, sign * kp.z_b_mm
    with matplotlib.rc_context({"svg.hashsalt": "stitchswitch", "svg.fonttype": "none"}):
        span = float(r.max())
        pad = 0.25 * max(h, 1.0)
        ylo, yhi = min(0.0, sign * h) - pad, max(0.0, sign * h) + pad
        height_in = min(6.0, max(2.4, 6.0 * (yhi - ylo) / (2.1 * span) + 1.2))
        fig, ax = plt.subplots(figsize=(7.0, height_in), dpi=120)
        for s in (-1.0, 1.0):
            ax.plot(s * r, z, color="0.55", lw=1.0)
            ax.plot(s * r[:n_in + 1], z[:n_in + 1], color="#b2182b", lw=2.6,
                    label="embroidered" if s > 0 else None)
        ax.axhline(0.0, color="0.7", lw=0.6, ls="--")
        ax.plot([0], [sign * h], "o", color="k", ms=4)
        ax.plot([-ra], [za], "s", color="#2166ac", ms=5, label="a (boundary)")
        ax.plot([rb], [zb], "D", color="#1b7837", ms=5, label="b (transition)")
        _dimension(ax, (0.0, 0.0), (0.0, sign * h), f"h = {h:.2f} mm", offset=(4, 0), ha="left",
                   at=0.8)
        _dimension(ax, (-ra, za), (0.0, za), f"r_a = {ra:.2f} mm",
                   offset=(0, 6 * sign), va="bottom" if sign > 0 else "top")
        _dimension(ax, (-ra - 0.12 * span, 0.0), (-ra - 0.12 * span, za), f"z_a = {abs(za):.2f} mm",
                   offset=(-4, 0), ha="right")
        _dimension(ax, (0.0, zb), (rb, zb), f"r_b = {rb:.2f} mm",
                   offset=(0, -6 * sign), va="top" if sign > 0 else "bottom")
        _dimension(ax, (rb + 0.12 * span, 0.0), (rb + 0.12 * span, zb), f"z_b = {abs(zb):.2f} mm",
                   offset=(4, 0), ha="left")
        ax.set_aspect("equal")
        ax.set_xlim(-1.05 * span, 1.05 * span)
        ax.set_ylim(ylo, yhi)
        ax.set_xlabel("r (mm, relaxed fabric)")
        ax.set_ylabel("z (mm)")
        ax.set_title(f"d = {profile.diameter_mm:g} mm, fill = {profile.fill:g}, popped {state}",
                     fontsize=10)
        source = "design map" if profile.source == "map" else "direct solve"
        caption = (f"material {material_name}; footprint d/eta = {profile.diameter_mm / eta:.1f} "
                   f"mm relaxed; b rule: {kp.b_rule}; profile from the {source}")
        ax.text(0.01, 0.02 if sign > 0 else 0.98, caption, transform=ax.transAxes, fontsize=7,
                color="0.35", va="bottom" if sign > 0 else "top")
        ax.legend(loc="upper right" if sign > 0 else "lower right", fontsize=7, frameon=False)
        return plot_bytes(fig, fmt.lstrip("."), bbox_inches="tight", pad_inches=0.1)


def write_figure(path, profile: PatchProfile, state: str = "up", material_name: str = "default",
                 eta: float = 1.7) -> None:
    ext = check_figure_path(path)
    atomic_write_bytes(path, figure_bytes(profile, ext, state, material_name, eta))


#: the section spans this many rim radii on each side of the patch centre
SECTION_REACH = 2.0


def section_segments(scene, patch_id: str):
    """The scene cut by the plane y = the patch's centre y: (segments (n, 2, 2) of (x, z) mm,
    owner (n,): the patch index of each segment, -1 on the flat fabric, rest (n,): the rest
    radius (mm) of each segment's midpoint on its patch, inf on the fabric)."""
    import numpy as np

    from stitchswitch.preview3d.render import _pyvista

    ids = [p.id for p in scene.patches]
    if patch_id not in ids:
        raise InvalidInputError(f"--patch: no patch {patch_id!r} in the design")
    pv = _pyvista()
    points, tris, data = scene.merged()
    mesh = pv.PolyData.from_regular_faces(points, tris)
    mesh.point_data["owner"] = data["patch_index"].astype(float)
    n_fabric = len(points) - sum(len(p.surface.points) for p in scene.patches)
    mesh.point_data["rest"] = np.concatenate([np.zeros(n_fabric)] + [
        p.surface.rest_radius_mm for p in scene.patches])
    cx, cy = scene.patches[ids.index(patch_id)].surface.centre_mm
    cut = mesh.slice(normal=(0.0, 1.0, 0.0), origin=(cx, cy, 0.0), generate_triangles=False)
    if cut.n_points == 0:
        return np.zeros((0, 2, 2)), np.zeros(0, dtype=int), np.zeros(0)
    lines = np.asarray(cut.lines).reshape(-1, 3)[:, 1:]
    xz = np.asarray(cut.points)[:, [0, 2]]
    owner = np.rint(np.asarray(cut.point_data["owner"])[lines[:, 0]]).astype(int)
    rest = np.asarray(cut.point_data["rest"])[lines].mean(axis=1)
    return xz[lines], owner, np.where(owner >= 0, rest, np.inf)


def section_bytes(scene, patch_id: str, size: tuple[int, int] = (1200, 600),
                  exaggerate: float = 1.0) -> bytes:
    """The PNG of the section view through patch ``patch_id`` (module docstring)."""
    import matplotlib
    matplotlib.use("Agg", force=False)
    import matplotlib.pyplot as plt
    import numpy as np
    from matplotlib.collections import LineCollection

    from stitchswitch.preview3d.overlay import height_note

    segs, owner, rest = section_segments(scene, patch_id)
    index = [p.id for p in scene.patches].index(patch_id)
    patch = scene.patches[index]
    cx, cy = patch.surface.centre_mm
    reach = SECTION_REACH * patch.surface.rim_radius_mm
    kp, sign = patch.profile.keypoints, (-1.0 if patch.state == "down" else 1.0)
    colour = "#b2182b" if sign > 0 else "#2166ac"
    w, h = size
    with matplotlib.rc_context({"svg.hashsalt": "stitchswitch"}):
        fig, ax = plt.subplots(figsize=(w / 100.0, h / 100.0), dpi=100, layout="constrained")
        mine = owner == index
        inside = mine & (rest <= patch.profile.boundary_radius_mm * (1 + 1e-9))
        for mask, c, lw, label in ((owner < 0, "0.7", 1.2, "fabric"),
                                   ((owner >= 0) & ~mine, "0.35", 1.2, "other patches"),
                                   (mine & ~inside, colour, 1.4, f"patch {patch_id}: blend"),
                                   (inside, colour, 3.0, f"patch {patch_id}: embroidered")):
            if mask.any():
                ax.add_collection(LineCollection(segs[mask], colors=c, linewidths=lw, label=label))
        z = segs[:, :, 1][np.abs(segs[:, :, 0] - cx).max(axis=1) <= reach] if len(segs) else []
        zlo, zhi = (min(0.0, float(np.min(z))), max(0.0, float(np.max(z)))) if len(z) else (-1, 1)
        pad = 0.15 * max(zhi - zlo, 1.0)
        _dimension(ax, (cx, 0.0), (cx, sign * kp.h_mm), f"h = {kp.h_mm:.2f} mm", offset=(4, 0),
                   ha="left", at=0.8)
        ax.axhline(0.0, color="0.8", lw=0.6, ls="--")
        ax.set_xlim(cx - reach, cx + reach)
        ax.set_ylim(zlo - pad, zhi + pad)
        ax.set_aspect(exaggerate, adjustable="box")
        ax.set_xlabel("x (mm, garment frame)")
        ax.set_ylabel("z (mm)")
        ax.set_title(f"section through patch {patch_id} at y = {cy:.1f} mm: d = "
                     f"{patch.profile.diameter_mm:g} mm, fill = {patch.profile.fill:g}, popped "
                     f"{patch.state}; {height_note(exaggerate)}", fontsize=10)
        ax.legend(loc="best", fontsize=8, frameon=False)
        return plot_bytes(fig)
