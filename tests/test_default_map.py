"""The shipped default map matches the current model and is smooth (or explains why not)."""
import numpy as np
import pytest

from stitchswitch import DEFAULT_MATERIAL, Patch, solve
from stitchswitch.reduced.design_space import smoothness as map_check
from stitchswitch.reduced.design_space.cache import default_map, map_for
from stitchswitch.reduced.design_space.design_map import (
    FLAG_BRANCH,
    FLAG_ONSET,
    FLAG_SMOOTH,
    FLAG_UNEXPLAINED,
)
from stitchswitch.reduced.design_space.precompute import DEFAULT_DIAMETERS_MM, DEFAULT_FILLS
from stitchswitch.reduced.model.material_io import material_hash
from stitchswitch.reduced.solvers.solve import DEFAULT_TOL


@pytest.fixture(scope="module")
def dmap():
    return default_map()


def test_default_map_is_for_the_default_material_and_grid(dmap):
    assert dmap.material == DEFAULT_MATERIAL
    assert dmap.material_hash == material_hash(DEFAULT_MATERIAL)
    assert np.array_equal(dmap.diameter_mm, DEFAULT_DIAMETERS_MM)
    assert np.array_equal(dmap.fill, DEFAULT_FILLS)
    assert dmap.shape == (86, 51)
    assert dmap.converged.all() and dmap.residual.max() <= DEFAULT_TOL
    assert map_for(DEFAULT_MATERIAL) is dmap


#: How far two certified solves of one design on the same branch may put the apex: the default
#: material's equilibria have a soft mode that moves h while the energy stays put. Measured over
#: the whole default map, warm-started map against cold direct solve: the energies agree to
#: 2.5e-16, r_b to 1.6e-8 mm, h only to 3.3e-5 mm (304 of 4,386 points beyond 1e-6 mm).
SOFT_H_MM = 1e-4


@pytest.mark.parametrize("i, j", [(0, 0), (10, 25), (40, 7), (85, 50), (60, 33)])
def test_default_map_matches_the_current_model(dmap, i, j):
    sol = solve(Patch(dmap.diameter_mm[i], dmap.fill[j]))
    assert dmap.energy[i, j] == pytest.approx(sol.energy, rel=1e-12, abs=1e-15)
    assert dmap.h_mm[i, j] == pytest.approx(sol.keypoints.h_mm, abs=SOFT_H_MM)
    assert dmap.r_b_mm[i, j] == pytest.approx(sol.keypoints.r_b_mm, abs=1e-6)


#: The designs before a jump of the map along its row where a direct (cold) solve may already be
#: on the branch after the jump (measured on the default map: only the design just before).
FOLD_WINDOW = 3


def test_the_map_follows_the_dome_and_direct_solves_differ_only_at_its_fold(dmap):
    """The row d = 54 mm crosses the band of fills where two popped branches coexist (the dome
    and the overhanging neck; the map's branch-change points, d 36-99 mm). The map holds the
    branch that continuation along increasing fill reaches (the dome, until it ends), whatever
    a cold solve's path would pick. A direct (cold) solve agrees with the map along the whole
    row (to the soft mode, ``SOFT_H_MM``) except within ``FOLD_WINDOW`` designs before the
    map's jump, where it may already land on the neck (the taller branch), certified."""
    i = int(np.flatnonzero(dmap.diameter_mm == 54.0)[0])
    h = dmap.h_mm[i]
    jumps = np.flatnonzero(np.diff(h) > 1.0) + 1
    assert jumps.size == 1                                  # the row does cross the band
    (jump,) = jumps
    for j, p in enumerate(dmap.fill):
        sol = solve(Patch(54.0, float(p)))
        if abs(sol.keypoints.h_mm - h[j]) > SOFT_H_MM:
            assert jump - FOLD_WINDOW <= j < jump, float(p)
            assert sol.certified and sol.keypoints.h_mm > h[j] + 1.0, float(p)


def test_every_unsmooth_point_is_flagged_and_explained(dmap):
    bad = map_check.violations(dmap.h_mm)
    assert np.array_equal(bad, dmap.flags != FLAG_SMOOTH)
    assert not np.any(dmap.flags == FLAG_UNEXPLAINED), [
        (float(dmap.diameter_mm[i]), float(dmap.fill[j]))
        for i, j in zip(*np.nonzero(dmap.flags == FLAG_UNEXPLAINED))]
    # with the small-patch refinement (docs/design-map.md) nothing is under-resolved: a flagged
    # point is the buckling onset (flat -> popped) of the small patches, or a change between
    # the two popped branches that coexist across a band of larger patches
    onset = dmap.flags == FLAG_ONSET
    assert np.all(onset[bad] | (dmap.flags[bad] == FLAG_BRANCH))
    d = dmap.diameter_mm[np.nonzero(onset)[0]]
    assert d.size == 0 or d.max() <= 30.0          # the onset only for the small patches


def test_query_accuracy_against_direct_solves(dmap):
    """Random off-grid designs whose cell has no flagged corner: h within 1 % or 0.05 mm."""
    rng = np.random.default_rng(11)
    checked = 0
    while checked < 25:
        d, p = rng.uniform(15.0, 100.0), rng.uniform(0.5, 1.0)
        i = min(np.searchsorted(dmap.diameter_mm, d) - 1, 84)
        j = min(np.searchsorted(dmap.fill, p) - 1, 49)
        if np.any(dmap.flags[i:i + 2, j:j + 2] != FLAG_SMOOTH):
            continue
        q = dmap.query(d, p)
        kp = solve(Patch(d, p)).keypoints
        assert abs(q.h_mm[0] - kp.h_mm) <= max(0.01 * kp.h_mm, 0.05), (d, p)
        checked += 1


def test_coarse_map_for_another_material_is_built_once_and_cached(tmp_path, monkeypatch):
    from stitchswitch.reduced.design_space.cache import COARSE_DIAMETERS_MM, COARSE_FILLS

    monkeypatch.setenv("STITCHSWITCH_CACHE", str(tmp_path))
    other = DEFAULT_MATERIAL.replace(w_b_emb=12.0)
    m = map_for(other, coarse=True)
    assert m.h_mm.shape == (COARSE_DIAMETERS_MM.size, COARSE_FILLS.size) == (18, 11)
    assert m.material_hash == material_hash(other) and m.converged.all()
    (cached,) = (tmp_path / "maps").glob("*-coarse.npz")
    assert np.array_equal(map_for(other, coarse=True).h_mm, m.h_mm)
    assert map_for(DEFAULT_MATERIAL, coarse=True) is default_map()     # the shipped map wins
    i, j = 5, 6                                                        # d 40, p 0.8
    sol = solve(Patch(40.0, 0.8), other)
    assert m.energy[i, j] == pytest.approx(sol.energy, rel=1e-12, abs=1e-15)
    assert m.h_mm[i, j] == pytest.approx(sol.keypoints.h_mm, abs=SOFT_H_MM)
