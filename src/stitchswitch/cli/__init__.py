"""The ``stitchswitch`` command line: a thin layer over the library, the top of the package.

``main`` holds the click group and loads each subcommand lazily; ``options`` holds the options and
the error handling shared by the subcommands; ``output`` the one ``key_value_table`` they print.
The subcommands live in one folder per layer they drive: ``model/``, ``reference/``,
``validation/`` and ``design/``. Library exceptions
(``InvalidInputError``) become one-line ``Error: ...`` messages with exit code 2 at this edge only.
"""
