"""Benchmark: DXF outline chaining and the import of a graded pattern file.

* chaining: closed outlines drawn as n separate LINEs (a 400 mm polygon's edges, shuffled, every
  other one reversed, ends moved by up to 0.05 mm or a tenth of an edge), joined by ``dxf.chain.chain_loops`` for n =
  1,000 to 30,000; the growth from the smallest to the largest n shows the order (n log n: about
  35x for 30x more lines; the former quadratic search: 900x, and 49 s at n = 3,000);
* the same 3,000-LINE outline through a DXF file (``import_dxf``, parsing included);
* a graded AAMA pattern file written here (17 pieces x 15 sizes, each boundary as four open
  POLYLINEs on layer 1, about 1 MB) through ``import_dxf``.

Targets: 3,000 LINEs chained in <= 1 s, the graded file imported in <= 3 s.

    python benchmarks/bench_dxf.py [--sizes 1000,3000,10000,30000] [--repeat 3] [--json]
"""
from __future__ import annotations

import argparse
import json
import pathlib
import tempfile
import time

import numpy as np


def shuffled_lines(n: int, seed: int = 0) -> list[np.ndarray]:
    t = 2 * np.pi * np.arange(n) / n
    ring = np.c_[400.0 * np.cos(t), 400.0 * np.sin(t)]
    rng = np.random.default_rng(seed)
    lines = [np.array([ring[i], ring[(i + 1) % n]]) for i in range(n)]
    jitter = min(0.05, 0.1 * 2 * np.pi * 400.0 / n)      # below the local snap tolerance
    lines = [(s[::-1] if i % 2 else s) + rng.uniform(-jitter, jitter, (2, 2))
             for i, s in enumerate(lines)]
    return [lines[i] for i in rng.permutation(n)]


def best_of(repeat: int, func) -> float:
    times = []
    for _ in range(repeat):
        t = time.perf_counter()
        func()
        times.append(time.perf_counter() - t)
    return min(times)


def lines_file(path: pathlib.Path, n: int) -> None:
    import ezdxf

    doc = ezdxf.new("R2010")
    doc.header["$INSUNITS"] = 4
    msp = doc.modelspace()
    for a, b in shuffled_lines(n, seed=1):
        msp.add_line(tuple(a), tuple(b))
    doc.saveas(path)


def graded_file(path: pathlib.Path, pieces: int = 17, sizes: int = 15, vertices: int = 40) -> None:
    """An AAMA file: one block per piece and size, the boundary split into four POLYLINEs."""
    import ezdxf

    doc = ezdxf.new("R12")
    msp = doc.modelspace()
    msp.add_text("Units: METRIC")
    for p in range(pieces):
        for s in range(sizes):
            name = f"P{p}_S{s}"
            blk = doc.blocks.new(name)
            blk.add_text(f"Piece Name: PIECE {p}", dxfattribs={"layer": "1"})
            blk.add_text(f"SIZE: {36 + 2 * s}", dxfattribs={"layer": "1"})
            t = 2 * np.pi * np.arange(vertices + 1) / vertices
            a, b = 150.0 + 10 * p + 3 * s, 100.0 + 5 * p + 2 * s
            ring = np.c_[a * np.cos(t) * (1 + 0.1 * np.cos(3 * t)), b * np.sin(t)]
            for q in np.array_split(np.arange(vertices + 1), 4):
                k = np.r_[q, q[-1] + 1] if q[-1] < vertices else q
                blk.add_polyline2d([tuple(v) for v in ring[k]], dxfattribs={"layer": "1"})
            blk.add_line((-a / 2, 0), (a / 2, 0), dxfattribs={"layer": "7"})
            msp.add_blockref(name, (1000.0 * p, 1000.0 * s))
    doc.saveas(path)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--sizes", default="1000,3000,10000,30000")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--json", action="store_true")
    args = ap.parse_args(argv)

    import logging

    from stitchswitch.layout.garment.dxf.chain import chain_loops
    from stitchswitch.layout.garment.dxf.reader import import_dxf

    logging.disable(logging.WARNING)
    sizes = [int(s) for s in args.sizes.split(",")]
    chain_loops(shuffled_lines(10), 0.5, "warm-up", "mm", 1.0)     # scipy's import is not chaining
    rows = []
    for n in sizes:
        lines, loops = shuffled_lines(n), []
        seconds = best_of(args.repeat, lambda lines=lines, loops=loops: loops.append(
            chain_loops(lines, 0.5, "bench", "mm", 1.0)))
        assert len(loops[-1]) == 1 and len(loops[-1][0]) == n
        rows.append({"lines": n, "chain_s": seconds})
    with tempfile.TemporaryDirectory() as tmp:
        tmp = pathlib.Path(tmp)
        lines_file(tmp / "lines.dxf", 3000)
        lines_import_s = best_of(args.repeat, lambda: import_dxf(tmp / "lines.dxf"))
        graded_file(tmp / "graded.dxf")
        graded_mb = (tmp / "graded.dxf").stat().st_size / 1e6
        pieces = []
        graded_s = best_of(args.repeat, lambda: pieces.append(import_dxf(tmp / "graded.dxf")))
        graded_pieces = len(pieces[-1])
    growth = rows[-1]["chain_s"] / rows[0]["chain_s"]
    three = next((r["chain_s"] for r in rows if r["lines"] == 3000), None)
    targets = {"3000_lines_chained_le_1s": three is not None and three <= 1.0,
               "graded_file_le_3s": graded_s <= 3.0}
    result = {"rows": rows, "growth": growth, "size_ratio": sizes[-1] / sizes[0],
              "lines_3000_import_s": lines_import_s, "graded_file_mb": graded_mb,
              "graded_pieces": graded_pieces, "graded_import_s": graded_s, "targets": targets}
    if args.json:
        print(json.dumps(result, indent=1))
        return 0
    print(f"{'LINEs':>8}{'chain s':>10}")
    print("-" * 18)
    for r in rows:
        print(f"{r['lines']:>8}{r['chain_s']:>10.3f}")
    print(f"growth {growth:.1f}x for {sizes[-1] / sizes[0]:g}x more lines")
    print(f"3,000 LINEs through a DXF file: {lines_import_s:.2f} s")
    print(f"graded AAMA file ({graded_mb:.2f} MB, {graded_pieces} pieces): {graded_s:.2f} s")
    for k, v in targets.items():
        print(f"target {k}: {'PASS' if v else 'FAIL'}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
