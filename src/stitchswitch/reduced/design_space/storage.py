"""Design maps on disk: one compressed ``.npz``, written atomically.

Arrays: ``diameter_mm`` (nd,), ``fill`` (np,); ``h_mm, r_a_mm, z_a_mm, r_b_mm, z_b_mm,
energy, residual`` (nd, np) float64; ``converged`` (nd, np) bool; the profiles ``u_mm``
(radial displacement r - R) and ``z_mm`` (nd, np, N), stored as int32 second differences along
the nodes of the values in units of ``profile_quantum_mm`` (1e-4 mm): smooth profiles then
compress about 6x better than float32 (1.7 MB against 9.7 MB for the default grid), and the
rounding (0.05 um) is far below any use; ``dr_mm`` and ``n_inside``
(nd,) for the node spacing of each diameter; ``flags`` (nd, np) int8 (the smoothness
explanation, ``design_map.FLAG_NAMES``); ``material_json`` and ``material_hash`` (the material
used, in canonical form, and its sha256); ``format`` (this module's version).
"""
from __future__ import annotations

import io
import os

import numpy as np

from stitchswitch.errors import InvalidInputError, StitchSwitchError
from stitchswitch.files.atomic import atomic_write_bytes
from stitchswitch.reduced.design_space.design_map import FLAG_NAMES, KEYPOINTS, DesignMap

FORMAT = "stitchswitch-design-map-1"
_TABLES = KEYPOINTS + ("energy", "residual")
PROFILE_QUANTUM_MM = 1e-4


def _encode(x: np.ndarray) -> np.ndarray:
    q = np.round(np.asarray(x, dtype=float) / PROFILE_QUANTUM_MM).astype(np.int64)
    d2 = np.diff(np.diff(q, axis=-1, prepend=0), axis=-1, prepend=0)
    if np.any(np.abs(d2) > np.iinfo(np.int32).max):
        raise StitchSwitchError(f"a profile is too large to store at {PROFILE_QUANTUM_MM} mm resolution")
    return d2.astype(np.int32)


def _decode(d2: np.ndarray) -> np.ndarray:
    q = np.cumsum(np.cumsum(d2.astype(np.int64), axis=-1), axis=-1)
    return (q * PROFILE_QUANTUM_MM).astype(np.float32)


def save_map(dmap: DesignMap, path: str | os.PathLike) -> None:
    from stitchswitch.reduced.model.material_io import canonical_json

    arrays = {name: getattr(dmap, name) for name in _TABLES}
    arrays.update(diameter_mm=dmap.diameter_mm, fill=dmap.fill, converged=dmap.converged,
                  u_mm=_encode(dmap.u_mm), z_mm=_encode(dmap.z_prof_mm),
                  profile_quantum_mm=np.array(PROFILE_QUANTUM_MM), dr_mm=dmap.dr_mm,
                  n_inside=dmap.n_inside, flags=dmap.flags,
                  material_json=np.array(canonical_json(dmap.material)),
                  material_hash=np.array(dmap.material_hash), format=np.array(FORMAT))
    buf = io.BytesIO()
    np.savez_compressed(buf, **arrays)
    atomic_write_bytes(path, buf.getvalue())


def load_map(path) -> DesignMap:
    """Read and check a map file completely, so that every query of the returned map works:
    a file that is not a readable ``.npz`` (truncated, a bad zip or zlib stream), that lacks an
    array or whose arrays have the wrong kind, shape or values (grids not strictly increasing,
    a non-finite table, a node count out of range), or whose material does not load or match
    its hash, raises one ``InvalidInputError`` naming the file and the problem."""
    from stitchswitch.reduced.model.material_io import material_from_json, material_hash

    where = f"design map {os.fspath(path)!r}"
    data = _read_npz(path, where)
    if _scalar_text(data.get("format")) != FORMAT:
        raise InvalidInputError(f"{where}: not a {FORMAT} file")
    missing = sorted(set(_KINDS) - set(data))
    if missing:
        raise InvalidInputError(f"{where}: missing array(s) {', '.join(missing)}")
    for name, kinds in _KINDS.items():
        if data[name].dtype.kind not in kinds:
            raise InvalidInputError(f"{where}: {name} has dtype {data[name].dtype}, expected "
                                    f"{_KIND_NAMES[kinds]}")
    _check_shapes(data, where)
    if float(data["profile_quantum_mm"]) != PROFILE_QUANTUM_MM:
        raise InvalidInputError(f"{where}: unsupported profile quantum "
                                f"{float(data['profile_quantum_mm']):g}")
    _check_values(data, where)
    material = material_from_json(_scalar_text(data["material_json"]), f"{where}: material")
    if material_hash(material) != _scalar_text(data["material_hash"]):
        raise InvalidInputError(f"{where}: the material hash does not match its material")
    return DesignMap(
        diameter_mm=data["diameter_mm"].astype(float), fill=data["fill"].astype(float),
        **{name: data[name].astype(float) for name in _TABLES},
        converged=data["converged"].astype(bool),
        u_mm=_decode(data["u_mm"]), z_prof_mm=_decode(data["z_mm"]),
        dr_mm=data["dr_mm"].astype(float), n_inside=data["n_inside"].astype(int),
        material=material, material_hash=_scalar_text(data["material_hash"]),
        flags=data["flags"].astype(np.int8))


#: The dtype kinds each array may have (f float, b bool, i/u integer, U text).
_KINDS = {**{name: "f" for name in _TABLES}, "diameter_mm": "f", "fill": "f", "dr_mm": "f",
          "profile_quantum_mm": "f", "converged": "b", "flags": "iu", "n_inside": "iu",
          "u_mm": "i", "z_mm": "i", "material_json": "U", "material_hash": "U", "format": "U"}
_KIND_NAMES = {"f": "floats", "b": "booleans", "iu": "integers", "i": "signed integers",
               "U": "text"}
#: The most a map may hold uncompressed (the default map holds 11 MB).
MAX_MAP_BYTES = 2 * 1024 ** 3


def _read_npz(path, where: str) -> dict:
    """Every array of the file, read with numpy's npz reader (no pickles), its declared
    uncompressed size bounded first."""
    import zipfile

    try:
        with zipfile.ZipFile(path) as z:
            total = sum(info.file_size for info in z.infolist())
        if total > MAX_MAP_BYTES:
            raise InvalidInputError(f"{where}: holds {total / 1024 ** 3:.1f} GiB uncompressed, "
                                    f"more than the limit of {MAX_MAP_BYTES / 1024 ** 3:g} GiB")
        with np.load(path, allow_pickle=False) as f:
            return {k: f[k] for k in f.files}
    except InvalidInputError:
        raise
    except OSError as exc:
        raise InvalidInputError(f"{where}: cannot be read ({exc.strerror or exc})") from None
    except Exception as exc:   # zipfile, zlib and numpy's header parser raise many types
        raise InvalidInputError(f"{where}: cannot be read as a .npz file "
                                f"({type(exc).__name__}: {str(exc)[:80]})") from None


def _scalar_text(value) -> str | None:
    """The text of a 0-d text array; None for anything else."""
    if value is None or value.shape != () or value.dtype.kind != "U":
        return None
    return str(value)


def _check_shapes(data: dict, where: str) -> None:
    nd, npp = (data[name].shape[0] if data[name].ndim else 0 for name in ("diameter_mm", "fill"))
    grid = (nd, npp)
    nodes = data["u_mm"].shape[2] if data["u_mm"].ndim == 3 else 0
    expected = {"diameter_mm": (nd,), "fill": (npp,), "dr_mm": (nd,), "n_inside": (nd,),
                **{name: grid for name in _TABLES + ("converged", "flags")},
                "u_mm": grid + (nodes,), "z_mm": grid + (nodes,), "profile_quantum_mm": (),
                "material_json": (), "material_hash": ()}
    for name, shape in expected.items():
        if data[name].shape != shape:
            raise InvalidInputError(f"{where}: {name} has shape {data[name].shape}, expected "
                                    f"{shape}")
    if nd < 2 or npp < 2 or nodes < 2:
        raise InvalidInputError(f"{where}: the grid is {nd} x {npp} designs of {nodes} nodes, "
                                "at least 2 x 2 of 2 nodes are needed to interpolate")


def _check_values(data: dict, where: str) -> None:
    for name in ("diameter_mm", "fill"):
        grid = data[name]
        if not np.all(np.isfinite(grid)) or np.any(np.diff(grid) <= 0):
            raise InvalidInputError(f"{where}: {name} is not a strictly increasing grid of "
                                    "finite numbers")
    for name in _TABLES + ("dr_mm",):
        if not np.all(np.isfinite(data[name])):
            raise InvalidInputError(f"{where}: {name} holds a value that is not finite")
    if np.any(data["dr_mm"] <= 0):
        raise InvalidInputError(f"{where}: dr_mm holds a node spacing <= 0")
    nodes = data["u_mm"].shape[2]
    n_inside = data["n_inside"]
    if np.any(n_inside < 1) or np.any(n_inside >= nodes):
        raise InvalidInputError(f"{where}: n_inside holds a boundary node outside [1, "
                                f"{nodes - 1}]")
    if not np.all(np.isin(data["flags"], list(FLAG_NAMES))):
        raise InvalidInputError(f"{where}: flags holds a code that is not one of "
                                f"{sorted(FLAG_NAMES)}")
