"""The reduced model itself (paper, section 4): parameters, discretization, energy, keypoints.

* ``params``: ``Patch`` (diameter_mm, fill) and ``Material`` (frozen, validated), ``DEFAULT_MATERIAL``.
* ``discretization``: ``make_grid(patch, material) -> Grid``, the rest-radius grid and the
  per-node coefficients (the fill-mixture law lives here, once: ``fill_mixture``).
* ``terms/``: one energy term per module, each a ``Term`` with its gradient and banded Hessian.
* ``assembly``: ``Model``, ``energy``, ``derivatives``: the terms summed.
* ``keypoints``: ``Keypoints`` and ``keypoints_from_profile``: h, (r_a, z_a), (r_b, z_b).
* ``material_io``: the material JSON file (``load_material``, ``save_material``, ``material_hash``).

The bottom layer of the package: it imports nothing from ``stitchswitch`` but ``errors``, ``files``.
"""
