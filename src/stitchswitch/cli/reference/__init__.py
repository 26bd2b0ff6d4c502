"""Subcommands of the shell references: ``fem-check`` (``fem_check``: the reduced model's model
error against the shell of revolution), ``fem-solve`` (``fem_solve``), ``switch-force``
(``switch_force``: snap-through by the contact plate) and ``bistability-map``
(``bistability_map``), over ``stitchswitch.fem_reference``; ``shell_options`` holds their
shared shell options.
"""
