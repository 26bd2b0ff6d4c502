"""The ``stitchswitch`` command line: a thin layer over the library.

``main`` holds the click group, ``options`` the options and error handling shared by the
subcommands, and each subcommand has its own module (``simulate``). Library exceptions
(``InvalidInputError``) become one-line ``Error: ...`` messages with exit code 2 at this edge only.
"""
