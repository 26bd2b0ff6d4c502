"""Progress on stderr, hidden by the group's ``-q``: bars (``bar``) and status lines
(``status``). With ``-q`` a command prints its result only (and errors)."""
from __future__ import annotations

import sys

import click

#: Key in the root click context's ``meta``: the verbosity (count of -v minus count of -q).
VERBOSITY = "stitchswitch.verbosity"


def verbosity() -> int:
    ctx = click.get_current_context(silent=True)
    return int(ctx.find_root().meta.get(VERBOSITY, 0)) if ctx is not None else 0


class _NoBar:
    """What ``bar`` gives under ``-q``: the attributes of click's bar, drawing nothing."""

    def __init__(self, length: int, label: str = ""):
        self.length, self.label, self.pos = length, label, 0

    def __enter__(self):
        return self

    def __exit__(self, *exc) -> None:
        return None

    def update(self, steps: int, current_item=None) -> None:
        self.pos += steps


def bar(length: int, label: str = "", **kwargs):
    """click's progress bar on stderr, or a silent stand-in under ``-q``."""
    if verbosity() < 0:
        return _NoBar(length, label)
    return click.progressbar(length=length, label=label, file=sys.stderr, **kwargs)


def status(message: str) -> None:
    """One progress line on stderr (not under ``-q``)."""
    if verbosity() >= 0:
        click.echo(message, err=True)
