"""The ``stitchswitch`` click group: version, verbosity, and the subcommands."""
from __future__ import annotations

import logging

import click

from stitchswitch import __version__
from stitchswitch.cli import options
from stitchswitch.cli.calibrate import calibrate
from stitchswitch.cli.fabricate import fabricate_cmd
from stitchswitch.cli.check import check
from stitchswitch.cli.demo import demo
from stitchswitch.cli.fem_check import fem_check_cmd
from stitchswitch.cli.fem_solve import fem_solve
from stitchswitch.cli.force import force
from stitchswitch.cli.import_cmd import import_cmd
from stitchswitch.cli.inspect_cmd import inspect
from stitchswitch.cli.inverse import inverse
from stitchswitch.cli.patch import patch
from stitchswitch.cli.place import place
from stitchswitch.cli.precompute import precompute
from stitchswitch.cli.preview import preview
from stitchswitch.cli.simulate import simulate
from stitchswitch.cli.switch_force import switch_force
from stitchswitch.cli.validate import validate


class _EchoHandler(logging.Handler):
    """Log records as ``Warning: message`` lines on click's (current) stderr."""

    def emit(self, record: logging.LogRecord) -> None:
        try:
            click.echo(f"{record.levelname.capitalize()}: {self.format(record)}", err=True)
        except Exception:  # pragma: no cover - logging must never raise
            self.handleError(record)


def configure_logging(verbosity: int) -> None:
    """Map verbosity (count of -v minus count of -q) to the level of the ``stitchswitch``
    logger: 0 warning (default), 1 info, 2+ debug, -1 error, -2 critical."""
    logger = logging.getLogger("stitchswitch")
    logger.setLevel(max(logging.DEBUG, logging.WARNING - 10 * verbosity))
    if not any(isinstance(h, _EchoHandler) for h in logger.handlers):
        logger.addHandler(_EchoHandler())


@click.group(cls=options.Group)
@click.version_option(__version__, "--version", prog_name="stitchswitch")
@options.verbose_opt
@options.quiet_opt
def cli(verbose: int, quiet: int) -> None:
    """Bistable embroidered textiles: simulate a circular embroidered patch with the reduced
    model. Lengths are in mm; diameters are measured on the pre-stretched fabric."""
    configure_logging(verbose - quiet)


cli.add_command(demo)
cli.add_command(simulate)
cli.add_command(precompute)
cli.add_command(inverse)
cli.add_command(force)
cli.add_command(validate)
cli.add_command(calibrate)
cli.add_command(fem_check_cmd)
cli.add_command(switch_force)
cli.add_command(fem_solve)
cli.add_command(patch)
cli.add_command(inspect)
cli.add_command(fabricate_cmd, name="fabricate")
cli.add_command(import_cmd)
cli.add_command(place)
cli.add_command(check)
cli.add_command(preview)
