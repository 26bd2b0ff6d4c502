"""Exceptions raised by the library. The CLI turns them into one-line messages."""


class StitchSwitchError(Exception):
    """Base class of every error the library raises on purpose."""


class InvalidInputError(StitchSwitchError, ValueError):
    """A parameter or input file is invalid. The message names the bad value."""
