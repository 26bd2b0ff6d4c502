"""Joining open curves into outlines (``dxf.chain``): many shuffled pieces, pieces shorter than
the snap tolerance, and the error of an end without a partner."""
import random
import time

import ezdxf
import numpy as np
import pytest

from stitchswitch.errors import InvalidInputError
from stitchswitch.layout.garment.dxf.chain import chain_loops
from stitchswitch.layout.garment.dxf.reader import import_dxf


def polygon(n, radius):
    t = 2 * np.pi * np.arange(n) / n
    return np.c_[radius * np.cos(t), radius * np.sin(t)]


def shuffled_lines(ring, seed=0, jitter=0.0):
    """The ring's edges as separate 2-point curves, shuffled, every other one reversed, ends
    moved by up to ``jitter``."""
    rng = np.random.default_rng(seed)
    n = len(ring)
    lines = [np.array([ring[i], ring[(i + 1) % n]]) for i in range(n)]
    lines = [seg[::-1] if i % 2 else seg for i, seg in enumerate(lines)]
    lines = [seg + rng.uniform(-jitter, jitter, seg.shape) for seg in lines]
    order = rng.permutation(n)
    return [lines[i] for i in order], order


def same_ring(a, b, atol):
    """a is b up to the starting point and the direction."""
    assert len(a) == len(b)
    k = int(np.argmin(np.hypot(*(b - a[0]).T)))
    for cand in (np.roll(b, -k, axis=0), np.roll(b[::-1], -(len(b) - 1 - k), axis=0)):
        if np.allclose(a, cand, atol=atol):
            return True
    return False


def test_3000_shuffled_lines_close_into_one_outline_quickly():
    ring = polygon(3000, 400.0)                         # edges of 0.84 mm
    lines, _ = shuffled_lines(ring, jitter=0.05)
    start = time.perf_counter()
    (out,) = chain_loops(lines, 0.5, "f.dxf", "mm", 1.0)
    elapsed = time.perf_counter() - start
    assert same_ring(out, ring, atol=0.2)
    assert elapsed < 2.0                                # the quadratic search took ~50 s


def test_3000_lines_through_a_dxf_file(tmp_path):
    doc = ezdxf.new("R2010")
    doc.header["$INSUNITS"] = 4
    msp = doc.modelspace()
    lines, _ = shuffled_lines(polygon(3000, 400.0), seed=1)
    for a, b in lines:
        msp.add_line(tuple(a), tuple(b))
    doc.saveas(tmp_path / "lines.dxf")
    (piece,) = import_dxf(tmp_path / "lines.dxf")
    assert len(piece.outline_mm) == 3000


@pytest.mark.parametrize("edge_mm", [0.3, 0.05])
def test_segments_shorter_than_the_snap_tolerance(edge_mm):
    """Edges shorter than the 0.5 mm tolerance: joined at their true neighbours, the outline
    does not close early on itself; two such outlines side by side stay two."""
    n = 400
    ring = polygon(n, edge_mm * n / (2 * np.pi))
    other = ring + [3 * ring[:, 0].max() + 5.0, 0.0]
    lines = shuffled_lines(ring, seed=2)[0] + shuffled_lines(other, seed=3)[0]
    loops = chain_loops(lines, 0.5, "f.dxf", "mm", 1.0)
    assert len(loops) == 2 and sorted(map(len, loops)) == [n, n]
    assert any(same_ring(loop, ring, 1e-9) for loop in loops)


def test_an_end_without_partner_names_its_gap_and_the_tolerance():
    ring = polygon(8, 50.0)
    lines, _ = shuffled_lines(ring)
    lines[3] = lines[3] + [[0.0, 0.0], [2.0, 0.0]]      # one end moved 2 mm off
    with pytest.raises(InvalidInputError) as info:
        chain_loops(lines, 0.5, "f.dxf: block 'B'", "mm", 1.0)
    message = str(info.value)
    assert message.startswith("f.dxf: block 'B': outline cannot be closed: gap of 2.000 mm")
    assert "exceeds the snap tolerance of 0.500 mm" in message
    short = [np.array([[0, 0], [0.2, 0]]), np.array([[0.2, 0], [0.2, 0.2]]),
             np.array([[0.2, 0.2], [0.0, 0.1]]), np.array([[0.0, 0.1], [0.0, 0.04]])]
    with pytest.raises(InvalidInputError) as info:                  # 0.04 mm gap, 0.06 mm curve
        chain_loops(short, 0.5, "f.dxf", "mm", 1.0)
    assert ("gap of 0.040 mm" in str(info.value)
            and "the tolerance there (half the length of the shorter curve) of 0.030 mm"
            in str(info.value))


def test_three_ends_at_one_point():
    a, b, c = np.array([0.0, 0.0]), np.array([10.0, 0.0]), np.array([0.0, 10.0])
    lines = [np.array([a, b]), np.array([b, c]), np.array([c, a]), np.array([a, [-5.0, -5.0]])]
    with pytest.raises(InvalidInputError, match=r"three or more curve ends meet at \(0, 0\) mm"):
        chain_loops(lines, 0.5, "f.dxf", "mm", 1.0)


def test_ring_starts_with_the_first_curve_in_its_direction():
    ring = polygon(6, 10.0)
    lines = [np.array([ring[i], ring[(i + 1) % 6]]) for i in range(6)]
    random.Random(0).shuffle(lines[1:])
    (out,) = chain_loops(lines, 0.5, "f", "mm", 1.0)
    assert np.array_equal(out[:2], lines[0])
