"""Where design maps come from: the shipped default map, or a per-material cache.

* The map of ``DEFAULT_MATERIAL`` over the default grid ships with the package
  (``stitchswitch/data/default_map.npz``, 1.9 MB), so the first query after installation only
  loads a file. ``tests/test_default_map.py`` checks that it matches the current model.
* Any other material's map is built once, on first use, into the cache directory
  (``$STITCHSWITCH_CACHE`` or ``~/.cache/stitchswitch``) under the material's sha256, and loaded
  from there afterwards.
"""
from __future__ import annotations

import os
from functools import lru_cache
from importlib import resources
from pathlib import Path

import numpy as np

from stitchswitch.reduced.design_space.design_map import DesignMap
from stitchswitch.reduced.model.params import DEFAULT_MATERIAL, Material


def default_map_path():
    return resources.files("stitchswitch") / "data" / "default_map.npz"


@lru_cache(maxsize=1)
def default_map() -> DesignMap:
    """The shipped map of the default material (loaded once per process)."""
    from stitchswitch.reduced.design_space.storage import load_map

    with resources.as_file(default_map_path()) as path:
        return load_map(path)


def cache_dir() -> Path:
    return Path(os.environ.get("STITCHSWITCH_CACHE") or Path.home() / ".cache" / "stitchswitch")


#: The coarse grid of ``map_for(..., coarse=True)``: d every 5 mm, p every 0.05 (18 x 11).
COARSE_DIAMETERS_MM = np.arange(15.0, 100.0 + 1e-9, 5.0)
COARSE_FILLS = np.round(np.arange(0.5, 1.0 + 1e-9, 0.05), 2)


def map_for(material: Material = DEFAULT_MATERIAL, workers: int = 1, progress=None,
            coarse: bool = False) -> DesignMap:
    """The default-grid map of ``material``: shipped, cached, or built now and cached. With
    ``coarse``, a material whose full map is neither shipped nor cached gets the coarse grid
    instead (``COARSE_*``, 198 solves, a few seconds, no smoothness check; cached too): enough
    for a figure."""
    from stitchswitch.reduced.design_space import precompute, storage
    from stitchswitch.reduced.model.material_io import material_hash

    if material == DEFAULT_MATERIAL:
        return default_map()
    path = cache_dir() / "maps" / f"{material_hash(material)}.npz"
    if path.exists():
        return storage.load_map(path)
    if coarse:
        path = cache_dir() / "maps" / f"{material_hash(material)}-coarse.npz"
        if path.exists():
            return storage.load_map(path)
        # no smoothness check: on a 5 mm x 0.05 grid the 2 % neighbour test does not apply
        dmap = precompute.build(material, COARSE_DIAMETERS_MM, COARSE_FILLS, workers=workers,
                                progress=progress, check=False)
    else:
        dmap = precompute.build(material, workers=workers, progress=progress)
    path.parent.mkdir(parents=True, exist_ok=True)
    storage.save_map(dmap, path)
    return dmap
