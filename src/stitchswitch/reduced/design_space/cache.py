"""Where design maps come from: the shipped default map, or a per-material cache.

* The map of ``DEFAULT_MATERIAL`` over the default grid ships with the package
  (``stitchswitch/data/default_map.npz``, 1.9 MB), so the first query after installation only
  loads a file. ``tests/test_default_map.py`` checks that it matches the current model.
* Any other material's map is built once, on first use, into the cache and loaded from there
  afterwards. The cache folder is ``$STITCHSWITCH_CACHE`` if set, else
  ``$XDG_CACHE_HOME/stitchswitch``, else ``~/.cache/stitchswitch`` (``cache_dir``); maps are
  ``maps/<sha256 of the material>.npz`` (full grid) and ``maps/<sha256>-coarse.npz``.

An entry is keyed by content (the sha256 of the material's canonical JSON) and verified by
content when read: ``storage.load_map`` checks the whole file (a readable npz with every array
of the right kind and shape, the stored material matching its stored hash), then the map must
hold the material asked for and the grid its name promises. An entry that fails (truncated, a
bad zip, another material's map copied under the name, an older format) is removed and rebuilt,
with one ``Warning:`` line on the ``stitchswitch`` logger saying why: never a traceback, never a
wrong map. A cache that cannot be written (a read-only folder, a path that is a file) does not
stop the command: the map is built and used without being stored, with a warning naming the
cache path and ``STITCHSWITCH_CACHE``.
"""
from __future__ import annotations

import logging
import os
import shutil
from functools import lru_cache
from importlib import resources
from pathlib import Path

import numpy as np

from stitchswitch.errors import InvalidInputError
from stitchswitch.reduced.design_space.design_map import DesignMap
from stitchswitch.reduced.model.params import DEFAULT_MATERIAL, Material

log = logging.getLogger(__name__)

__all__ = ["default_map", "default_map_path", "cache_dir", "map_path", "cached_map", "map_for",
           "COARSE_DIAMETERS_MM", "COARSE_FILLS"]


def default_map_path():
    return resources.files("stitchswitch") / "data" / "default_map.npz"


@lru_cache(maxsize=1)
def default_map() -> DesignMap:
    """The shipped map of the default material (loaded once per process)."""
    from stitchswitch.reduced.design_space.storage import load_map

    with resources.as_file(default_map_path()) as path:
        return load_map(path)


def cache_dir() -> Path:
    """``$STITCHSWITCH_CACHE``, else ``$XDG_CACHE_HOME/stitchswitch``, else
    ``~/.cache/stitchswitch``."""
    if os.environ.get("STITCHSWITCH_CACHE"):
        return Path(os.environ["STITCHSWITCH_CACHE"])
    base = os.environ.get("XDG_CACHE_HOME") or Path.home() / ".cache"
    return Path(base) / "stitchswitch"


#: The coarse grid of ``map_for(..., coarse=True)``: d every 5 mm, p every 0.05 (18 x 11).
COARSE_DIAMETERS_MM = np.arange(15.0, 100.0 + 1e-9, 5.0)
COARSE_FILLS = np.round(np.arange(0.5, 1.0 + 1e-9, 0.05), 2)


def map_path(material: Material, coarse: bool = False) -> Path:
    """The cache entry of ``material``'s map (full or coarse grid)."""
    from stitchswitch.reduced.model.material_io import material_hash

    return cache_dir() / "maps" / f"{material_hash(material)}{'-coarse' if coarse else ''}.npz"


def _grid(coarse: bool) -> tuple[np.ndarray, np.ndarray]:
    from stitchswitch.reduced.design_space import precompute

    return ((COARSE_DIAMETERS_MM, COARSE_FILLS) if coarse
            else (precompute.DEFAULT_DIAMETERS_MM, precompute.DEFAULT_FILLS))


def _mismatch(dmap: DesignMap, material: Material, coarse: bool) -> str | None:
    """Why a loaded entry is not the map asked for, or None."""
    from stitchswitch.reduced.model.material_io import material_hash

    if dmap.material != material or dmap.material_hash != material_hash(material):
        return f"it holds the map of another material (sha256 {dmap.material_hash[:12]})"
    d, p = _grid(coarse)
    if not (np.array_equal(dmap.diameter_mm, d) and np.allclose(dmap.fill, p, rtol=0, atol=1e-9)):
        return (f"its grid ({dmap.diameter_mm.size} x {dmap.fill.size}) is not the "
                f"{'coarse' if coarse else 'default'} grid")
    return None


def _discard(path: Path, why: str) -> None:
    try:
        if path.is_dir() and not path.is_symlink():
            shutil.rmtree(path)
        else:
            path.unlink()
        log.warning("design-map cache %r: %s; removed, the map is rebuilt", str(path), why)
    except OSError as exc:
        log.warning("design-map cache %r: %s and it cannot be removed (%s); the map is rebuilt "
                    "without it", str(path), why, exc.strerror or type(exc).__name__)


def cached_map(material: Material, coarse: bool = False) -> DesignMap | None:
    """``material``'s map from the cache if a valid entry holds it, else None (a bad entry is
    removed with a warning). Never builds one."""
    from stitchswitch.reduced.design_space import storage

    path = map_path(material, coarse)
    try:
        present = path.exists() or path.is_symlink()
    except OSError:
        present = False
    if not present:
        return None
    if path.is_dir():
        _discard(path, "it is a folder, not a map file")
        return None
    try:
        dmap = storage.load_map(path)
    except InvalidInputError as exc:
        problem = str(exc).partition(": ")[2] or str(exc)
        _discard(path, f"it is not a valid map ({problem})")
        return None
    why = _mismatch(dmap, material, coarse)
    if why is not None:
        _discard(path, why)
        return None
    return dmap


def _writable_maps_dir(path: Path) -> bool:
    """Create the entry's folder and test that a file can be written there; warn if not."""
    from stitchswitch.files.outputs import check_output_file

    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        check_output_file(path, what="design-map cache")
        return True
    except (OSError, InvalidInputError) as exc:
        why = (str(exc) if isinstance(exc, InvalidInputError) else
               f"design-map cache {str(path.parent)!r}: {exc.strerror or type(exc).__name__}")
        log.warning("%s; the map is built without being stored (set STITCHSWITCH_CACHE to a "
                    "writable folder to keep it)", why)
        return False


def _store(dmap: DesignMap, path: Path) -> None:
    from stitchswitch.reduced.design_space import storage

    try:
        storage.save_map(dmap, path)
    except OSError as exc:
        log.warning("design-map cache %r: the map could not be stored (%s)", str(path),
                    exc.strerror or type(exc).__name__)


def map_for(material: Material = DEFAULT_MATERIAL, workers: int = 1, progress=None,
            coarse: bool = False) -> DesignMap:
    """The default-grid map of ``material``: shipped, cached, or built now and cached. With
    ``coarse``, a material whose full map is neither shipped nor cached gets the coarse grid
    instead (``COARSE_*``, 198 solves, a few seconds, no smoothness check; cached too): enough
    for a figure."""
    from stitchswitch.reduced.design_space import precompute

    if material == DEFAULT_MATERIAL:
        return default_map()
    dmap = cached_map(material)
    if dmap is not None:
        return dmap
    if coarse:
        dmap = cached_map(material, coarse=True)
        if dmap is not None:
            return dmap
    path = map_path(material, coarse)
    store = _writable_maps_dir(path)        # warned before the build, not after it
    d, p = _grid(coarse)
    # coarse: no smoothness check; on a 5 mm x 0.05 grid the 2 % neighbour test does not apply
    dmap = precompute.build(material, d, p, workers=workers, progress=progress, check=not coarse)
    if store:
        _store(dmap, path)
    return dmap
