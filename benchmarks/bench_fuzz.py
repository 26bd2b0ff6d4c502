"""Benchmark: the loaders against generated bad input (fuzzing).

Every loader of a user's file gets corrupted copies of real files (the shipped data in
``src/stitchswitch/data``, the external fixtures in ``tests/data/external``, a map and a design
written here), made by the functions the fuzz tests use (``tests/fuzz_edits.py``): byte edits
(bit flips, inserted and deleted runs, zeroed runs, truncation) and structured edits (CSV and
DXF lines deleted, repeated or replaced and cells replaced by nasty values; one JSON value
replaced by a wrong type, a 5,000-digit or out-of-range number, deep nesting, a long or
control-character string, a key removed or added; a map's arrays replaced by ones of the wrong
kind, shape or values). Each case is loaded once, in this process, with a
10 s alarm:

* crash: the loader raised anything but ``InvalidInputError``;
* bad message: an ``InvalidInputError`` of 300 characters or more (the file's path not
  counted) or one that does not name the file;
* hang: the case took more than 10 s (the alarm fired);
* partial file: a command that failed left output behind.

The CLI group runs a sample of corrupted files through the commands that read them
(``import``, ``inspect``, ``check``, ``simulate --material``, ``force --data``, ``inverse
--map``) with click's runner: exit code 2 must print exactly one ``Error:`` line (its message
checked as above) and leave the output folder empty; a traceback is a crash.

A loaded map is queried at a random point of its domain, with profiles (a map that loads must
answer). Target: 0 crashes, 0 bad messages, 0 hangs, 0 partial files over >= 10,000 cases. Cases are generated
from ``--seed``, so a run is repeatable; the first case of every distinct failure is written
to ``--keep`` (default: not kept) for replay.

    python benchmarks/bench_fuzz.py [--cases 10500] [--seed 0] [--keep DIR] [--json]
"""
from __future__ import annotations

import argparse
import collections
import json
import logging
import pathlib
import random
import signal
import sys
import tempfile
import time
import traceback

import numpy as np

ROOT = pathlib.Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests"))
from fuzz_edits import byte_edit, json_edit, line_edit, map_edit  # noqa: E402  the shared edits

DATA = ROOT / "src" / "stitchswitch" / "data"
EXTERNAL = ROOT / "tests" / "data" / "external"
HANG_S = 10.0
MAX_MESSAGE = 300

class Hang(Exception):
    """The alarm of a case that ran longer than HANG_S."""


# --- loaders and their seeds -------------------------------------------------------------

def _design_seed() -> bytes:
    return json.dumps({
        "version": 1,
        "pieces": [{"name": "front", "size": "M", "source": "bench",
                    "outline_mm": [[0, 0], [300, 0], [300, 250], [0, 250]]}],
        "patches": [{"id": "a", "piece": "front", "centre_mm": [60, 60], "diameter_mm": 24,
                     "fill": 0.8, "conductive": "ring:0", "state": "up"},
                    {"id": "b", "piece": "front", "centre_mm": [150, 120], "diameter_mm": 40,
                     "fill": 0.7, "composite": {"core_diameter_mm": 20, "core_fill": 0.9},
                     "outline_mm": [[-20, 0], [0, -20], [20, 0], [0, 20]]}],
        "material": {"name": "default"}, "machine": {"name": "janome-550e", "hoop": "SQ14b"},
    }, indent=1).encode()


def _map_seed(tmp: pathlib.Path) -> bytes:
    from stitchswitch import DEFAULT_MATERIAL
    from stitchswitch.reduced.design_space import precompute, storage

    dmap = precompute.build(DEFAULT_MATERIAL, np.array([40.0, 41.0, 42.0]), np.array([0.7, 0.75, 0.8]))
    storage.save_map(dmap, tmp / "seed.npz")
    return (tmp / "seed.npz").read_bytes()


def _load_map(path):
    from stitchswitch.reduced.design_space.storage import load_map

    dmap = load_map(path)
    d, p = dmap.diameter_mm, dmap.fill
    dmap.query(d[0] + 0.37 * (d[-1] - d[0]), p[0] + 0.61 * (p[-1] - p[0]), profiles=True)
    return dmap


class PartialOutput(Exception):
    """A command that failed left (part of) its output behind."""


class BadErrorOutput(Exception):
    """A command that exited 2 printed something else than one ``Error:`` line."""


def _command(path: pathlib.Path, out: pathlib.Path) -> list[str]:
    """The command that reads the case ``path`` (named after its seed), writing into ``out``."""
    name = path.name
    if name.endswith(".dxf") or name.endswith(".DXF"):
        return ["import", str(path), "-o", str(out / "design.json")]
    if name.endswith("design.json"):
        return ["check", str(path), "--json"]
    if name.endswith("material.json"):
        return ["simulate", "--material", str(path), "--json"]
    if name.endswith(".csv"):
        return ["force", "-d", "40", "-p", "0.8", "--data", str(path), "--json"]
    if name.endswith(".npz"):
        return ["inverse", "--height", "5", "--count", "1", "--map", str(path), "--json"]
    return ["inspect", str(path)]


def run_cli(path: pathlib.Path):
    """The command of ``path`` through click's runner: a crash re-raises its exception, exit
    code 2 must print one ``Error:`` line and leave nothing in the output folder (an
    ``InvalidInputError`` of that line is raised, for the message checks); 0 (and 1 for
    ``check``: violations) are loads."""
    from click.testing import CliRunner

    from stitchswitch.cli.main import cli
    from stitchswitch.errors import InvalidInputError

    out = path.parent / "out"
    out.mkdir(exist_ok=True)
    for old in out.iterdir():
        old.unlink()
    args = _command(path, out)
    result = CliRunner().invoke(cli, args)
    if result.exception is not None and not isinstance(result.exception, SystemExit):
        raise result.exception
    if result.exit_code == 2:
        left = sorted(p.name for p in out.iterdir())
        if left:
            raise PartialOutput(f"{args[0]} left {', '.join(left)}")
        lines = result.output.strip().splitlines()
        if len(lines) != 1 or not lines[0].startswith("Error: ") or "Traceback" in result.output:
            raise BadErrorOutput(f"{args[0]}: {result.output[:120]!r}")
        if args[0] == "inverse" and "is not achievable" in lines[0]:
            return                                   # a valid map's answer about the target
        raise InvalidInputError(lines[0][len("Error: "):])
    if result.exit_code not in (0, 1 if args[0] == "check" else 0):
        raise BadErrorOutput(f"{args[0]} exited {result.exit_code}: {result.output[:120]!r}")


def groups(tmp: pathlib.Path) -> dict:
    """name -> (loader, suffix, [(seed name, bytes, [edit functions])])."""
    from stitchswitch.layout.embroidery.export import supported_formats
    from stitchswitch.layout.embroidery.file_summary import summarise
    from stitchswitch.layout.embroidery.machines import load_machines
    from stitchswitch.layout.garment.design_io import load_design
    from stitchswitch.layout.garment.dxf.reader import import_dxf
    from stitchswitch.reduced.design_space.force_model import load_force_csv
    from stitchswitch.reduced.model.material_io import load_material
    from stitchswitch.validation.measured import load_measurements

    def csv(rng, seed):
        return line_edit(rng, seed, ",")

    def dxf(rng, seed):
        return line_edit(rng, seed, "\n")

    def read(path):
        return path.read_bytes()

    formats = supported_formats()
    return {
        "measured CSV": (load_measurements, ".csv",
                         [("measured_synthetic.csv", read(DATA / "measured_synthetic.csv"),
                           [byte_edit, csv, csv])]),
        "force CSV": (load_force_csv, ".csv",
                      [("force_synthetic.csv", read(DATA / "force_synthetic.csv"),
                        [byte_edit, csv, csv])]),
        "material JSON": (load_material, ".json",
                          [("default_material.json", read(DATA / "default_material.json"),
                            [byte_edit, json_edit, json_edit])]),
        "design JSON": (load_design, ".json",
                        [("design.json", _design_seed(), [byte_edit, json_edit, json_edit])]),
        "machines JSON": (lambda p: load_machines(p, formats), ".json",
                          [("machines.json", read(DATA / "machines.json"),
                            [byte_edit, json_edit, json_edit])]),
        "map npz": (_load_map, ".npz",
                    [("map (3 x 3 built here)", _map_seed(tmp), [byte_edit, map_edit, map_edit]),
                     ("default_map.npz", read(DATA / "default_map.npz"), [byte_edit])]),
        "DXF": (import_dxf, ".dxf",
                [(p.name, read(p), [byte_edit, dxf, dxf])
                 for p in sorted((EXTERNAL / "dxf").iterdir()) if p.stat().st_size < 20_000]),
        "embroidery": (summarise, None,
                       [(p.name, read(p), [byte_edit])
                        for p in sorted((EXTERNAL / "embroidery").iterdir())]),
        "CLI": (run_cli, None,
                [("clo-box_R10.dxf", read(EXTERNAL / "dxf" / "clo-box_R10.dxf"), [byte_edit, dxf]),
                 ("Star.DST", read(EXTERNAL / "embroidery" / "Star.DST"), [byte_edit]),
                 ("design.json", _design_seed(), [byte_edit, json_edit]),
                 ("material.json", read(DATA / "default_material.json"), [byte_edit, json_edit]),
                 ("force.csv", read(DATA / "force_synthetic.csv"), [byte_edit, csv]),
                 ("map.npz", _map_seed(tmp), [byte_edit, map_edit])]),
    }


# --- running -------------------------------------------------------------------------------

def _alarm(signum, frame):
    raise Hang()


def run_case(load, path: pathlib.Path):
    """('ok' | 'refused' | 'crash' | 'message' | 'hang' | 'partial', detail, seconds)."""
    from stitchswitch.errors import InvalidInputError

    signal.setitimer(signal.ITIMER_REAL, HANG_S)
    start = time.perf_counter()
    try:
        load(path)
        outcome, detail = "ok", ""
    except Hang:
        outcome, detail = "hang", "more than 10 s"
    except PartialOutput as exc:
        outcome, detail = "partial", str(exc)
    except InvalidInputError as exc:
        message = str(exc).replace(str(path), "<file>")
        if len(message) >= MAX_MESSAGE or "<file>" not in message and path.name not in message:
            outcome, detail = "message", f"{len(message)} characters: {message[:160]}"
        else:
            outcome, detail = "refused", ""
    except Exception as exc:
        frames = [f for f in traceback.extract_tb(exc.__traceback__) if "stitchswitch" in f.filename]
        where = f"{pathlib.Path(frames[-1].filename).name}:{frames[-1].lineno}" if frames else "?"
        outcome, detail = "crash", f"{type(exc).__name__} at {where}: {str(exc)[:120]}"
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
    return outcome, detail, time.perf_counter() - start


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--cases", type=int, default=10_500, help="in all, shared by the groups")
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--keep", type=pathlib.Path, default=None,
                    help="folder for the first case of every distinct failure")
    ap.add_argument("--json", action="store_true")
    args = ap.parse_args(argv)

    logging.disable(logging.CRITICAL)             # ezdxf's recover messages, repairs
    np.seterr(all="ignore")
    signal.signal(signal.SIGALRM, _alarm)
    rng = random.Random(args.seed)
    rows, failures = [], {}
    with tempfile.TemporaryDirectory() as tmp:
        tmp = pathlib.Path(tmp)
        table = groups(tmp)
        share = {"map npz": 0.07, "DXF": 0.1, "embroidery": 0.1, "CLI": 0.05}
        rest = (1.0 - sum(share.values())) / (len(table) - len(share))
        t0 = time.perf_counter()
        for name, (load, suffix, seeds) in table.items():
            n = round(args.cases * share.get(name, rest))
            counts, slowest = collections.Counter(), 0.0
            for _ in range(n):
                seed_name, seed, edits = rng.choice(seeds)
                data = rng.choice(edits)(rng, seed)
                path = tmp / ("case" + suffix if suffix else f"case-{seed_name}")
                path.write_bytes(data)
                outcome, detail, seconds = run_case(load, path)
                counts[outcome] += 1
                slowest = max(slowest, seconds)
                if outcome in ("crash", "message", "hang", "partial"):
                    key = (name, detail.split(":")[0] if outcome == "crash" else outcome)
                    if key not in failures:
                        failures[key] = {"group": name, "outcome": outcome, "seed": seed_name,
                                         "detail": detail}
                        if args.keep:
                            args.keep.mkdir(parents=True, exist_ok=True)
                            keep = args.keep / f"{len(failures):03d}-{path.name}"
                            keep.write_bytes(data)
                            failures[key]["kept"] = str(keep)
            rows.append({"group": name, "cases": n, "loaded": counts["ok"],
                         "refused": counts["refused"], "crashes": counts["crash"],
                         "bad_messages": counts["message"], "hangs": counts["hang"],
                         "partial_files": counts["partial"], "slowest_s": slowest})
        elapsed = time.perf_counter() - t0
    total = {k: sum(r[k] for r in rows) for k in ("cases", "loaded", "refused", "crashes",
                                                   "bad_messages", "hangs", "partial_files")}
    target = total["cases"] >= 10_000 and not any(
        total[k] for k in ("crashes", "bad_messages", "hangs", "partial_files"))
    result = {"seed": args.seed, "rows": rows, "total": total, "elapsed_s": elapsed,
              "failures": list(failures.values()), "target_met": target}
    if args.json:
        print(json.dumps(result, indent=1))
        return 0
    head = (f"{'group':<15}{'cases':>7}{'loaded':>8}{'refused':>9}{'crashes':>9}"
            f"{'bad msg':>9}{'hangs':>7}{'partial':>9}{'slowest s':>11}")
    print(head)
    print("-" * len(head))
    for r in rows + [dict(group="all", slowest_s=max(r["slowest_s"] for r in rows), **total)]:
        print(f"{r['group']:<15}{r['cases']:>7}{r['loaded']:>8}{r['refused']:>9}"
              f"{r['crashes']:>9}{r['bad_messages']:>9}{r['hangs']:>7}{r['partial_files']:>9}"
              f"{r['slowest_s']:>11.2f}")
    print(f"{elapsed:.0f} s in all")
    for f in failures.values():
        print(f"  {f['group']}: {f['outcome']} ({f['seed']}): {f['detail']}")
    print(f"target 0 crashes / 0 bad messages / 0 hangs / 0 partial files on >= 10,000 cases: "
          f"{'PASS' if target else 'FAIL'}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
