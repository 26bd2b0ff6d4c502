"""The shell of revolution's options shared by ``fem-check``, ``fem-solve``, ``switch-force``
and ``bistability-map``: its own physics (Poisson ratio, natural curvature, thickness) and its
mesh, turned into a ``ShellParams``."""
from __future__ import annotations

import click

from stitchswitch.cli import options

NU = options.BoundedFloat(-1.0, 0.5, low_open=True)
KAPPA0 = options.BoundedFloat(-1.0, 1.0)
THICKNESS = options.BoundedFloat(0.0, 10.0, low_open=True)


def shell_options(f):
    """``--poisson``, ``--kappa0``, ``--thickness-mm`` and ``--elements``, in that order in
    ``--help``."""
    f = click.option("--elements", type=click.IntRange(min=4, max=400), default=40, show_default=True,
                     metavar="N", help="Cubic Hermite elements of the shell on the patch, in [4, 400].")(f)
    f = click.option("--thickness-mm", "thickness_mm", type=THICKNESS, default=None, metavar="MM",
                     help="Bending rigidity from a thickness, D = sqrt(A_s A_t) t^2 / 12, instead "
                     f"of the material's calibrated bending weights; in {THICKNESS.range_text}.")(f)
    f = click.option("--kappa0", "kappa0_per_mm", type=KAPPA0, default=0.0, show_default=True,
                     metavar="PER_MM", help="Natural curvature of the embroidered layer (1/mm; "
                     f"> 0 curves it like the pop-up dome), in {KAPPA0.range_text}.")(f)
    return click.option("--poisson", "nu", type=NU, default=0.3, show_default=True, metavar="NU",
                        help=f"Poisson ratio of the shell, in {NU.range_text}.")(f)


def shell_params(nu: float, kappa0_per_mm: float, thickness_mm: float | None, elements: int):
    from stitchswitch.fem_reference.revolution.params import ShellParams

    return ShellParams(nu=nu, kappa0_per_mm=kappa0_per_mm, thickness_mm=thickness_mm,
                       elements_inside=elements)
