"""The demos by name."""
from __future__ import annotations

from stitchswitch.errors import InvalidInputError


def _demos() -> dict:
    from stitchswitch.demos.forearm import FOREARM_INTERFACE
    from stitchswitch.demos.tennis_pocket import TENNIS_POCKET

    return {d.name: d for d in (TENNIS_POCKET, FOREARM_INTERFACE)}


DEMOS = ("tennis-pocket", "forearm-interface")


def get_demo(name: str):
    demos = _demos()
    if name not in demos:
        raise InvalidInputError(f"unknown demo {name!r}; the demos are {', '.join(DEMOS)}")
    return demos[name]
