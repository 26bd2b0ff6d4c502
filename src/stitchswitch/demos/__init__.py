"""Built-in end-to-end demos: the paper's two applications (section 6).

``stitchswitch demo`` runs ``tennis-pocket`` (6.1), ``stitchswitch demo forearm-interface`` the
programmable garment interface (6.2). Each goes from a target to a machine file: inverse design
on the design-space map, placement on a garment piece, the constraint check, the 3D preview,
hoop grouping and JEF export, and a one-page HTML summary (``pipeline.run_demo``).
"""
from stitchswitch.demos.registry import DEMOS, get_demo

__all__ = ["DEMOS", "get_demo"]
