"""Subcommands of the design and fabrication workflow: ``import`` (``import_cmd``), ``place``,
``check``, ``preview``, ``patch``, ``inspect`` (``inspect_cmd``), ``fabricate`` and ``demo``, over
``stitchswitch.layout``, ``stitchswitch.preview3d`` and ``stitchswitch.demos``.
"""
