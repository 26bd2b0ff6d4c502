"""The studio server's long-lived objects, kept out of Python's full garbage collections.

Once the page is built, the server holds about 230,000 objects that live as long as it does
(VTK, trame, numba's kernels, the design-space map). Each full collection of the cyclic
garbage collector scanned them all and held the event loop for about 80 ms (the 40-patch
benchmark design), a visible hitch whenever one came due during a slider drag.
``freeze_long_lived`` collects once and then moves every surviving object to the
collector's permanent generation (``gc.freeze``): a full collection then scans only the
objects made since, and garbage made after the freeze is still collected.
"""
from __future__ import annotations

import gc


def freeze_long_lived() -> int:
    """Collect, then freeze what survives; returns how many objects are frozen."""
    gc.collect()
    gc.freeze()
    return gc.get_freeze_count()
