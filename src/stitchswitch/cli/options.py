"""Options and error handling shared by the subcommands (rasterio's ``rio/options.py`` is the model).

Bad input of any kind, a click usage error or an ``InvalidInputError`` from the library, is
reported as the single line ``Error: <message>`` on stderr with exit code 2: no usage block, no
traceback. Subcommands get this by being ``Command`` instances (the group's default class).

Every output file option has the type ``OutputFile``: its path is checked while the options
are parsed, before the command computes anything (``files.outputs.check_output_file``); the
command then writes all its files as one unit with ``files.outputs.together``.
"""
from __future__ import annotations

import math
import pathlib

import click

from stitchswitch.errors import InvalidInputError
from stitchswitch.files.outputs import check_output_file
from stitchswitch.reduced.model.params import DIAMETER_RANGE_MM, SOLVERS


class InputError(click.ClickException):
    """Bad input: shown as one line ``Error: <message>``, exit code 2 (like click usage errors)."""

    exit_code = 2

    def __init__(self, message: str) -> None:
        super().__init__(" ".join(str(message).splitlines()))


class _OneLineErrors:
    """Mixin for click commands: usage errors and library input errors become ``InputError``."""

    def parse_args(self, ctx: click.Context, args: list[str]) -> list[str]:
        try:
            return super().parse_args(ctx, args)
        except click.exceptions.NoArgsIsHelpError:
            raise
        except click.UsageError as exc:
            raise InputError(exc.format_message()) from None

    def invoke(self, ctx: click.Context):
        try:
            return super().invoke(ctx)
        except InvalidInputError as exc:
            raise InputError(str(exc)) from None


class Command(_OneLineErrors, click.Command):
    """A subcommand whose input errors are one line."""


class Group(_OneLineErrors, click.Group):
    """The group; its subcommands default to ``Command``."""

    command_class = Command


class FiniteFloat(click.ParamType):
    """A float that rejects nan and inf by name (click.FLOAT accepts 'nan')."""

    name = "float"

    def convert(self, value, param, ctx) -> float:
        try:
            v = float(value)
        except (TypeError, ValueError):
            self.fail(f"{value!r} is not a number", param, ctx)
        if not math.isfinite(v):
            self.fail(f"{value!r} is not a finite number", param, ctx)
        return v


FINITE_FLOAT = FiniteFloat()


class BoundedFloat(FiniteFloat):
    """A finite float inside [low, high] (or open at ``low`` with ``low_open``): an option whose
    value past its range would make a command run away or compute nonsense."""

    def __init__(self, low: float, high: float, *, low_open: bool = False):
        self.low, self.high, self.low_open = low, high, low_open
        self.range_text = f"{'(' if low_open else '['}{low:g}, {high:g}]"

    def convert(self, value, param, ctx) -> float:
        v = super().convert(value, param, ctx)
        if v < self.low or v > self.high or (self.low_open and v == self.low):
            self.fail(f"{v:g} is outside {self.range_text}", param, ctx)
        return v


class OutputFile(click.ParamType):
    """An output file path, refused at parse time (one ``Error:`` line naming the option and the
    path, exit code 2) if it cannot be written or, with ``extensions``, has another extension.
    Converts to ``pathlib.Path`` (or ``str`` with ``as_str``)."""

    name = "file"

    def __init__(self, extensions: tuple[str, ...] | None = None, hint: str = "",
                 as_str: bool = False):
        self.extensions, self.hint, self.as_str = extensions, hint, as_str

    def convert(self, value, param, ctx):
        what = param.opts[0] if param is not None and param.opts else "output"
        try:
            path = check_output_file(value, self.extensions, what, self.hint)
        except InvalidInputError as exc:
            raise InputError(str(exc)) from None
        return str(value) if self.as_str else path


verbose_opt = click.option(
    "--verbose", "-v", count=True, help="More log messages on stderr (-v info, -vv debug).")
quiet_opt = click.option(
    "--quiet", "-q", count=True, help="Fewer log messages on stderr (-q hides warnings).")

diameter_opt = click.option(
    "--diameter", "-d", "diameter_mm", type=FINITE_FLOAT, default=40.0, show_default=True,
    metavar="MM",
    help="Patch diameter in mm, measured on the pre-stretched fabric; supported range "
         f"[{DIAMETER_RANGE_MM[0]:g}, {DIAMETER_RANGE_MM[1]:g}].")
fill_opt = click.option(
    "--fill", "-p", type=FINITE_FLOAT, default=0.8, show_default=True, metavar="P",
    help="Fill fraction of the embroidery, in (0, 1].")
material_opt = click.option(
    "--material", "material_path", type=click.Path(path_type=pathlib.Path), default=None,
    metavar="FILE",
    help="Material JSON file (format: stitchswitch/data/default_material.json). "
         "Default: the built-in material.")
solver_opt = click.option(
    "--solver", type=click.Choice(SOLVERS), default="newton", show_default=True,
    help="newton: certified projected Newton; adam: the paper's projected Adam baseline.")
max_iter_opt = click.option(
    "--max-iter", type=click.IntRange(min=1), default=None, metavar="N",
    help="Iteration budget: Newton iterations (default 500) or Adam steps (default 20000).")
json_opt = click.option(
    "--json", "as_json", is_flag=True, help="Print one JSON object instead of the table.")


def inverse_target_opts(when: str = ""):
    """The options of an inverse-design target besides its height, as ``InverseTarget`` takes
    them: ``--radius`` (``radius_mm``), ``--max-diameter`` (``max_diameter_mm``) and
    ``--min-fill`` (``min_fill``), each None when not given. ``when`` starts each help text
    (e.g. "With --height: " for a command where they apply only with that option)."""
    def cap(text: str) -> str:
        return when + text if when else text[0].upper() + text[1:]

    radius = click.option(
        "--radius", "radius_mm", type=FINITE_FLOAT, default=None, metavar="MM",
        help=cap("target boundary radius r_a in mm (optional)."))
    max_diameter = click.option(
        "--max-diameter", "max_diameter_mm", type=FINITE_FLOAT, default=None, metavar="MM",
        help=cap("largest allowed diameter in mm [default: the map's largest]."))
    min_fill = click.option(
        "--min-fill", "min_fill", type=FINITE_FLOAT, default=None, metavar="P",
        help=cap("smallest allowed fill [default: the map's smallest]."))

    def decorator(f):
        return radius(max_diameter(min_fill(f)))
    return decorator


def deprecated_alias(old: str, new: str):
    """A hidden option ``old`` kept for old scripts: its value goes to ``new``'s parameter with
    one ``Warning:`` line on stderr (so that ``--json`` output stays clean). Give it the same
    ``type`` through ``**kwargs`` of the returned decorator factory."""
    def callback(ctx, param, value):
        if value is None:
            return None
        click.echo(f"Warning: {old} is deprecated; use {new}", err=True)
        return value

    def decorator(dest: str, **kwargs):
        return click.option(old, dest, default=None, hidden=True, expose_value=True,
                            callback=callback, **kwargs)
    return decorator


def one_of(new_value, old_value, new: str, old: str):
    """The value of an option given under its name or its deprecated alias (not both)."""
    if new_value is not None and old_value is not None:
        raise InputError(f"give {new} or the deprecated {old}, not both")
    value = new_value if new_value is not None else old_value
    if value is None:
        raise InputError(f"Missing option '{new}'.")
    return value
