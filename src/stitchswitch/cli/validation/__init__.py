"""Subcommands on measured data: ``validate`` and ``discover``, over ``stitchswitch.validation``.
"""
