"""Benchmark: the machine files of 18 designs, measured as an embroiderer would sign them off.

The designs (all 5 mm triangles unless said; conductive as given):

* 12 plain patches, d in {20, 40, 60, 100} mm x p in {0.3, 0.6, 0.9}, conductive ``ring:0,1``;
* the three forearm buttons of the forearm-interface demo (soft d 51 p 0.7198, medium d 44
  p 0.9997, firm d 59 p 0.9908; the demo's inverse-design choices on the default map),
  conductive ``ring:0`` (the demo's electrodes);
* d 40 p 0.6 at 2 mm triangles, ``ring:0,1`` (the finest lattice: the most gaps);
* d 100 p 0.6, conductive ``annulus:20:30`` (an electrode ring of many pieces);
* the firm button off-centre, centred at (65, 0) mm in the RE20b hoop (like a garment hooping:
  nothing left of the hoop centre), ``ring:0``.

Each is planned with the default stitch parameters, exported to JEF, DST, PES, EXP and VP3 (the
bytes must decode with pyembroidery to the plan's stitch count), and measured
(``layout.embroidery.sewing.audit``): gap crossings (thread segments over unstitched fabric;
count and length outside the stitched pieces), trims, stitches < 0.3 mm outside ties, ties and
their fewest stitches and shortest stitch, the stitch-graph components of each electrode (1 =
one continuous conductor), and the largest difference between the header extents and the
decoded stitch bounds relative to the hoop centre in JEF and DST (mm). The totals line also
counts the designs whose JEF, read back by pyembroidery, names the threads (palette name and
Janome number per colour block) that ``layout.embroidery.jef_palette`` names for them.

Targets: per design, gap-crossing length at most half of the "before" table's at no more trims
in total; 0 short stitches; every tie >= 3 stitches; every electrode 1 component; header errors
<= 0.1 mm. ``cross+trims`` shows why the first cannot be met together: every piece is an island,
so every move between pieces is a crossing or a trim (docs/embroidery.md, "The route").
``--json`` prints the rows as JSON.

    python benchmarks/bench_stitches.py [--json] [--only NAME] [--travel stitch|jump|trim]
"""
from __future__ import annotations

import argparse
import io
import json
import re
import struct

import numpy as np

#: (name, d mm, fill, resolution mm, conductive, centre in the hoop mm, hoop)
DESIGNS = tuple(
    [(f"d{d} p{p}", d, p, 5.0, "ring:0,1", (0.0, 0.0), None)
     for d in (20, 40, 60, 100) for p in (0.3, 0.6, 0.9)]
    + [("soft d51", 51, 0.7198, 5.0, "ring:0", (0.0, 0.0), None),
       ("medium d44", 44, 0.9997, 5.0, "ring:0", (0.0, 0.0), None),
       ("firm d59", 59, 0.9908, 5.0, "ring:0", (0.0, 0.0), None),
       ("d40 p0.6 res2", 40, 0.6, 2.0, "ring:0,1", (0.0, 0.0), None),
       ("d100 annulus", 100, 0.6, 5.0, "annulus:20:30", (0.0, 0.0), None),
       ("firm off-centre", 59, 0.9908, 5.0, "ring:0", (65.0, 0.0), "RE20b")])

FORMATS = ("jef", "dst", "pes", "exp", "vp3")


def _decoded_bounds(data: bytes, fmt: str) -> tuple[float, float, float, float]:
    """(xmin, ymin, xmax, ymax) in mm, y up, of the STITCH records pyembroidery reads."""
    import pyembroidery as pe
    reader = {"jef": pe.read_jef, "dst": pe.read_dst}[fmt]
    pattern = reader(io.BytesIO(data), {"trims": True} if fmt == "jef" else None)
    pts = np.array([(s[0], s[1]) for s in pattern.stitches if s[2] & pe.COMMAND_MASK == pe.STITCH])
    x, y = pts[:, 0] / 10.0, -pts[:, 1] / 10.0
    return float(x.min()), float(y.min()), float(x.max()), float(y.max())


def header_error_mm(data: bytes, fmt: str) -> float:
    """Largest |header extent - decoded extent| (mm): JEF's left, top, right, bottom distances
    from the hoop centre (int32 at byte 36), DST's +X, -X, +Y, -Y."""
    x0, y0, x1, y1 = _decoded_bounds(data, fmt)
    if fmt == "jef":
        left, top, right, bottom = struct.unpack_from("<4i", data, 36)
        header = np.array([left, top, right, bottom]) / 10.0
        truth = np.array([-x0, y1, x1, -y0])
    else:
        text = data[:512].decode("latin-1")
        field = {k: int(v) for k, v in re.findall(r"([+-][XY]):\s*(-?\d+)", text)}
        header = np.array([field["+X"], field["-X"], field["+Y"], field["-Y"]]) / 10.0
        truth = np.array([x1, -x0, y1, -y0])
    return float(np.abs(header - truth).max())


def _stitch_count(data: bytes, fmt: str) -> int:
    import pyembroidery as pe
    reader = getattr(pe, f"read_{fmt}")
    pattern = reader(io.BytesIO(data), {"trims": True} if fmt == "jef" else None)
    return sum(1 for s in pattern.stitches if s[2] & pe.COMMAND_MASK == pe.STITCH)


def jef_threads_as_named(data: bytes, plan) -> bool:
    """Whether the threads pyembroidery's reader finds in the JEF (palette name and Janome
    number per colour block) are those ``jef_palette`` names for the plan's threads (what the
    fabrication sheet and ``stitchswitch patch`` print)."""
    import pyembroidery as pe

    from stitchswitch.layout.embroidery.jef_palette import jef_threads
    read = pe.read_jef(io.BytesIO(data), {"trims": True}).threadlist
    named = jef_threads([t.rgb for t in plan.threads])
    return [(t.description, t.catalog_number) for t in read] == [(t.name, t.number) for t in named]


def run_one(design, travel: str = "stitch") -> dict:
    from stitchswitch.layout.embroidery import export
    from stitchswitch.layout.embroidery.machines import default_machine
    from stitchswitch.layout.embroidery.patch_geometry import make_patch, parse_selection
    from stitchswitch.layout.embroidery.sewing.audit import audit
    from stitchswitch.layout.embroidery.stitches import StitchParams, plan_stitches

    name, d, p, res, cond, centre, hoop_name = design
    geom = make_patch(float(d), float(p), res, parse_selection(cond))
    prm = StitchParams() if travel == "stitch" else StitchParams(travel=travel)
    plan = plan_stitches(geom, prm, centre)
    machine = default_machine()
    hoop = machine.hoop(hoop_name) if hoop_name else machine.choose_hoop(d, d)
    offset = np.asarray(centre)
    pieces = [q + offset for q in geom.pieces_mm]
    a = audit(plan, pieces, geom.conductive, geom.centroids_mm + offset, res)
    files = {fmt: export.encode(plan, fmt, hoop) for fmt in FORMATS}
    decodes = all(_stitch_count(files[f], f) >= plan.stitch_count for f in FORMATS)
    row = {"design": name, "pieces": geom.n_triangles, "stitches": plan.stitch_count}
    row.update(a.as_dict())
    row.update({"moves": a.gap_crossings + a.trims, "electrodes": len(a.electrode_components),
                "max_components": max(a.electrode_components, default=0),
                "jef_header_err_mm": round(header_error_mm(files["jef"], "jef"), 2),
                "dst_header_err_mm": round(header_error_mm(files["dst"], "dst"), 2),
                "all_formats_decode": decodes,
                "jef_threads_as_named": jef_threads_as_named(files["jef"], plan)})
    return row


COLUMNS = (("design", "design", "{}"), ("pieces", "pieces", "{}"),
           ("stitches", "stitches", "{}"), ("gap_crossings", "crossings", "{}"),
           ("gap_crossing_mm", "cross mm", "{:.1f}"), ("trims", "trims", "{}"),
           ("moves", "cross+trims", "{}"),
           ("short_stitches", "<0.3mm", "{}"), ("ties", "ties", "{}"),
           ("min_tie_stitches", "tie st", "{}"), ("min_tie_stitch_mm", "tie mm", "{:.2f}"),
           ("max_components", "electrode comp", "{}"),
           ("jef_header_err_mm", "JEF hdr err", "{:.1f}"),
           ("dst_header_err_mm", "DST hdr err", "{:.1f}"))


def table(rows) -> str:
    cells = [[h for _, h, _ in COLUMNS]] + [[f.format(r[k]) for k, _, f in COLUMNS] for r in rows]
    widths = [max(len(c[i]) for c in cells) for i in range(len(COLUMNS))]
    lines = ["| " + " | ".join(c.ljust(w) for c, w in zip(cells[0], widths)) + " |",
             "|" + "|".join("-" * (w + 2) for w in widths) + "|"]
    lines += ["| " + " | ".join(c.ljust(w) for c, w in zip(row, widths)) + " |" for row in cells[1:]]
    total_mm = sum(r["gap_crossing_mm"] for r in rows)
    lines.append(f"\ntotal: {sum(r['gap_crossings'] for r in rows)} crossings, {total_mm:.1f} mm; "
                 f"{sum(r['trims'] for r in rows)} trims; "
                 f"{sum(r['short_stitches'] for r in rows)} short stitches; all formats decode: "
                 f"{all(r['all_formats_decode'] for r in rows)}; JEF threads as named: "
                 f"{sum(r['jef_threads_as_named'] for r in rows)}/{len(rows)}")
    return "\n".join(lines)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--json", action="store_true")
    ap.add_argument("--only", default=None, help="run only the design of this name")
    ap.add_argument("--travel", default="stitch", choices=("stitch", "jump", "trim"),
                    help="the travel between neighbouring pieces (default: the default)")
    args = ap.parse_args(argv)
    designs = [x for x in DESIGNS if args.only in (None, x[0])]
    rows = [run_one(x, args.travel) for x in designs]
    print(json.dumps(rows, indent=2) if args.json else table(rows))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
