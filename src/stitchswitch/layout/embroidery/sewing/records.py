"""The needle record kinds of a stitch plan (``stitches.StitchPlan.commands``): ``STITCH``
(move and penetrate), ``JUMP`` (move with the needle up), ``TRIM`` (cut the thread),
``COLOR_CHANGE`` (stop for the next thread) and the final ``END``."""

STITCH, JUMP, TRIM, COLOR_CHANGE, END = 0, 1, 2, 3, 4
