"""The studio server's heap (``heap.freeze_long_lived``): what lives at the start is frozen out
of the full collections, and garbage made afterwards is still collected."""
import gc

import pytest

from stitchswitch.studio.heap import freeze_long_lived


@pytest.fixture
def unfrozen():
    yield
    gc.unfreeze()


class Node:
    def __init__(self):
        self.other = None


def cycle():
    a, b = Node(), Node()
    a.other, b.other = b, a


def test_long_lived_objects_are_frozen_and_new_garbage_is_collected(unfrozen):
    kept = [Node() for _ in range(1000)]
    frozen = freeze_long_lived()
    assert frozen == gc.get_freeze_count() and frozen > len(kept)
    scanned = {id(o) for o in gc.get_objects()}
    assert not any(id(k) in scanned for k in kept)         # out of the collections' scans
    cycle()
    assert gc.collect() >= 2                   # the new cycle's two nodes
