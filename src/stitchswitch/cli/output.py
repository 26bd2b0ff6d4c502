"""Text the subcommands print: one way to lay out an aligned ``key  value`` table."""
from __future__ import annotations


def key_value_table(rows, gap: int = 2) -> str:
    """One line per ``(key, value)`` pair: the keys left-aligned to the longest one, then
    ``gap`` spaces, then the value (no trailing newline)."""
    rows = list(rows)
    width = max(len(key) for key, _ in rows)
    return "\n".join(f"{key:<{width}}{' ' * gap}{value}" for key, value in rows)
