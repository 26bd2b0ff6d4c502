"""The options of the shell reference shared by ``fem-check`` and ``fem-solve``: which physics
the reference adds (hoop bending, Poisson coupling) and where its Newton solve starts."""
from __future__ import annotations

import click

from stitchswitch.cli import options
from stitchswitch.fem_reference.continuation import DEFAULT_START, STARTS

#: The Poisson ratios of an isotropic elastic sheet.
POISSON = options.BoundedFloat(-1.0, 0.5, low_open=True)


def shell_options(f):
    """``--hoop-bending``, ``--poisson`` and ``--start``, in that order in ``--help``."""
    f = click.option("--start", type=click.Choice(STARTS), default=DEFAULT_START, show_default=True,
                     help="Start of the reference's Newton solve: the reduced model's equilibrium, "
                     "or the prestretch continuation from the flat sheet (independent of the "
                     "reduced model).")(f)
    f = click.option("--poisson", type=POISSON, default=0.0, show_default=True,
                     help="Poisson coupling of the reference's bending (with --hoop-bending), "
                     f"in {POISSON.range_text}.")(f)
    return click.option("--hoop-bending", is_flag=True, help="Hoop (parallel) bending in the "
                        "reference only (the reduced model has none): what the reduced model "
                        "leaves out.")(f)
