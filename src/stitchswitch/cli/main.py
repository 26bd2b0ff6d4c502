"""The ``stitchswitch`` click group: version, verbosity, and the subcommands."""
from __future__ import annotations

import logging

import click

from stitchswitch import __version__
from stitchswitch.cli import options, progress

#: Subcommand name -> "module:attribute". A subcommand's module is imported only when that
#: subcommand runs (or help lists it), so that e.g. ``check`` does not load the solver, the
#: FEM code and pyvista (click's documented lazy-loading pattern).
COMMANDS = {
    "demo": "design.demo:demo",
    "simulate": "model.simulate:simulate",
    "precompute": "model.precompute:precompute",
    "inverse": "model.inverse:inverse",
    "force": "model.force:force",
    "validate": "validation.validate:validate",
    "calibrate": "model.calibrate:calibrate",
    "sensitivity": "model.sensitivity:sensitivity",
    "discover": "validation.discover:discover",
    "fem-check": "reference.fem_check:fem_check_cmd",
    "switch-force": "reference.switch_force:switch_force",
    "fem-solve": "reference.fem_solve:fem_solve",
    "bistability-map": "reference.bistability_map:bistability_map_cmd",
    "patch": "design.patch:patch",
    "inspect": "design.inspect_cmd:inspect",
    "fabricate": "design.fabricate:fabricate_cmd",
    "import": "design.import_cmd:import_cmd",
    "place": "design.place:place",
    "edit": "design.edit:edit",
    "layout": "design.layout_cmd:layout_cmd",
    "remove": "design.edit:remove",
    "check": "design.check:check",
    "preview": "design.preview:preview",
    "studio": "studio:studio",
}


#: ``stitchswitch --help`` lists the commands by workflow, in this order; a command of
#: ``COMMANDS`` named in no section is listed under "other" (so registering one needs no edit
#: here).
SECTIONS = {
    "design": ("studio", "import", "place", "edit", "remove", "check", "layout", "preview",
               "inverse", "demo"),
    "predict": ("simulate", "force", "sensitivity", "precompute"),
    "data": ("validate", "calibrate", "discover"),
    "fabricate": ("fabricate", "patch", "inspect"),
    "reference": ("fem-check", "fem-solve", "switch-force", "bistability-map"),
}


class LazyGroup(options.Group):
    def list_commands(self, ctx):
        return list(COMMANDS)

    def format_commands(self, ctx, formatter):
        """The commands under their workflow's heading (``SECTIONS``)."""
        listed = [n for names in SECTIONS.values() for n in names]
        sections = dict(SECTIONS)
        other = tuple(n for n in COMMANDS if n not in listed)
        if other:
            sections["other"] = other
        limit = formatter.width - 6 - max(len(n) for n in COMMANDS)
        for title, names in sections.items():
            rows = []
            for name in names:
                cmd = self.get_command(ctx, name)
                if cmd is not None and not cmd.hidden:
                    rows.append((name, cmd.get_short_help_str(limit)))
            if rows:
                with formatter.section(f"Commands: {title}"):
                    formatter.write_dl(rows)

    def get_command(self, ctx, name):
        if name not in COMMANDS:
            return None
        from importlib import import_module

        module, attr = COMMANDS[name].split(":")
        return getattr(import_module(f"stitchswitch.cli.{module}"), attr)


class _EchoHandler(logging.Handler):
    """Log records as ``Warning: message`` lines on click's (current) stderr."""

    def emit(self, record: logging.LogRecord) -> None:
        try:
            click.echo(f"{record.levelname.capitalize()}: {self.format(record)}", err=True)
        except Exception:  # pragma: no cover - logging must never raise
            self.handleError(record)


def configure_logging(verbosity: int) -> None:
    """Map verbosity (count of -v minus count of -q) to the level of the ``stitchswitch``
    logger: 0 warning (default), 1 info, 2+ debug, -1 error, -2 critical. Native libraries'
    console output, ezdxf's log and Python warnings (numpy's RuntimeWarning) come through it
    at info level (``native_output``): shown with -v, never on a default run."""
    from stitchswitch.native_output import relay_library_logs

    logger = logging.getLogger("stitchswitch")
    logger.setLevel(max(logging.DEBUG, logging.WARNING - 10 * verbosity))
    if not any(isinstance(h, _EchoHandler) for h in logger.handlers):
        logger.addHandler(_EchoHandler())
    relay_library_logs(logging.getLogger("stitchswitch.libraries"))


@click.group(cls=LazyGroup)
@click.version_option(__version__, "--version", prog_name="stitchswitch")
@options.verbose_opt
@options.quiet_opt
def cli(verbose: int, quiet: int) -> None:
    """Bistable embroidered textiles: simulate a circular embroidered patch with the reduced
    model. Lengths are in mm; diameters are measured on the pre-stretched fabric."""
    click.get_current_context().meta[progress.VERBOSITY] = verbose - quiet
    configure_logging(verbose - quiet)
