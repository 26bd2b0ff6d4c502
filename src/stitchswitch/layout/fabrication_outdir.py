"""The fabrication folder is written as a whole (``stitchswitch.outdir``): a non-empty target
is refused unless ``force``; nothing half-written is left on an error."""
from stitchswitch.outdir import building, check_outdir, write_outdir

__all__ = ["building", "check_outdir", "write_outdir"]
