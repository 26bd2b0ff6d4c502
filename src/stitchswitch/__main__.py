"""``python -m stitchswitch``: the same as the ``stitchswitch`` command."""
from stitchswitch.cli.main import cli

if __name__ == "__main__":
    cli(prog_name="stitchswitch")
