"""The design space (d, p): the precomputed map, its queries, inverse design and the force model.

* ``design_map``: ``DesignMap`` and its real-time ``query``; ``precompute``: ``build`` the map;
  ``smoothness``: the neighbour check and the explanation of every point that is not smooth;
  ``storage``: ``save_map`` / ``load_map`` (``.npz``); ``cache``: ``default_map`` (shipped) and
  ``map_for(material)`` (per-material cache); ``heatmap``: ``plot_height_map`` (the paper's Fig. 4).
* ``inverse``: ``inverse_design(InverseTarget) -> InverseResult``; ``inverse_mip``: its selection
  step as a mixed-integer program.
* ``force_model``: the switching-force polynomial model (Appendix B).

Imports ``reduced.model`` and ``reduced.solvers``.
"""
