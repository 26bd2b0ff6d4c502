"""Subcommands of the reduced model: ``simulate``, ``precompute``, ``inverse``, ``force``,
``calibrate``. Each module holds one click command; it parses, calls ``stitchswitch.reduced`` and
prints.
"""
