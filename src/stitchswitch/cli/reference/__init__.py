"""Subcommands of the shell reference: ``fem-check`` (``fem_check``), ``fem-solve``
(``fem_solve``) and ``switch-force`` (``switch_force``), over ``stitchswitch.fem_reference``.
"""
