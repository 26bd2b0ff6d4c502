import meshio
import numpy as np
import pytest

from stitchswitch import InvalidInputError, Patch, solve
from stitchswitch.files.revolution import surface_of_revolution, write_mesh


@pytest.mark.parametrize("ext", [".vtu", ".ply", ".obj"])
def test_revolved_profile_round_trips_through_meshio(tmp_path, ext):
    sol = solve(Patch(40.0, 0.8))
    points, tris = surface_of_revolution(sol.r_mm, sol.z_mm, n_theta=48)
    assert points.shape == (1 + (sol.r_mm.size - 1) * 48, 3)
    path = tmp_path / f"dome{ext}"
    write_mesh(path, points, tris, {"height_mm": points[:, 2]} if ext == ".vtu" else None)
    mesh = meshio.read(path)
    assert mesh.points.shape[0] == points.shape[0]
    height = mesh.points[:, 2].max() - mesh.points[:, 2].min()
    assert height == pytest.approx(sol.keypoints.h_mm, abs=0.01)
    assert [p.name for p in tmp_path.iterdir()] == [path.name]          # no temporary left


def test_bad_inputs(tmp_path):
    with pytest.raises(InvalidInputError, match="pole"):
        surface_of_revolution(np.array([1.0, 2.0]), np.array([0.0, 0.0]))
    with pytest.raises(InvalidInputError, match="extension"):
        write_mesh(tmp_path / "mesh", np.zeros((3, 3)), np.array([[0, 1, 2]]))
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("ext", [".ply", ".obj", ".vtu"])
def test_the_same_mesh_gives_the_same_bytes(tmp_path, ext, monkeypatch):
    import datetime

    import meshio
    points, tris = surface_of_revolution(np.linspace(0, 10, 5), np.linspace(3, 0, 5))
    write_mesh(tmp_path / f"a{ext}", points, tris)

    class Later(datetime.datetime):
        @classmethod
        def now(cls, tz=None):
            return datetime.datetime(2031, 5, 6, 7, 8, 9, 123456)
    import types
    for module in ("meshio.ply._ply", "meshio.obj._obj"):      # a later clock
        monkeypatch.setattr(f"{module}.datetime", types.SimpleNamespace(datetime=Later))
    write_mesh(tmp_path / f"b{ext}", points, tris)
    assert (tmp_path / f"a{ext}").read_bytes() == (tmp_path / f"b{ext}").read_bytes()
    assert b"2031" not in (tmp_path / f"b{ext}").read_bytes()[:400]
    assert len(meshio.read(tmp_path / f"b{ext}").points) == len(points)
