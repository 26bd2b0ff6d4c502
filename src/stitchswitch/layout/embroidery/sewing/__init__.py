"""The thread of a stitch plan: what goes where and how the needle gets there.

* ``records``: the needle record kinds (``STITCH``, ``JUMP``, ``TRIM``, ``COLOR_CHANGE``, ``END``);
* ``fills``: ``fill_piece``, one convex piece as tatami or satin with underlay and pull
  compensation;
* ``routing``: ``route``, the order of the pieces of a thread block and the kind of every move
  (Warnsdorff over the gap graph, centre outward, electrodes as one thread), ``crossing`` (the
  shortest way across a gap) and ``electrode_regions``;
* ``runs``: ``Builder``, thread runs with the stitch hygiene (0.1 mm grid, minimum stitch,
  locks, trims);
* ``audit``: ``audit``, a plan measured as an embroiderer and the mechanism see it (gap
  crossings, trims, short stitches, ties, electrode connectivity).

``layout.embroidery.stitches`` puts them together (``plan_stitches``); nothing here imports it.
"""
