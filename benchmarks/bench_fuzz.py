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

The output sample runs the commands that write files (``precompute``, ``calibrate``,
``patch``, ``preview``, ``simulate --profile-csv``, ``import``, ``place``, ``discover --json``,
``validate --report``, ``fabricate -o``) with a bad output path (a missing folder, a file as
folder, an unwritable folder, a directory, a wrong extension): exit code 2 with one ``Error:``
line naming the path, and nothing written.

The SIGKILL sample starts a writing command (``precompute --out --plot``, ``patch -o
--preview``, ``calibrate --out``, ``preview -o --mesh``, ``simulate --profile-csv``,
``fabricate -o``, ``validate --report``) in a subprocess, with or without a previous output in
place, and kills it at a random time (half of the kills in the last quarter of the run,
where the files are written). Every final output must then be absent, the previous one
untouched, or complete (byte-identical to a complete run, or for files that carry timings,
parseable with the same keys); a command's outputs must all be old or all new (a partial
file). The command is then run again to completion, which must succeed, leave complete
outputs and no temporary file or folder of the package (a leftover temp).

A loaded map is queried at a random point of its domain, with profiles (a map that loads must
answer). Target: 0 crashes, 0 bad messages, 0 hangs, 0 partial files over >= 10,000 cases. Cases are generated
from ``--seed``, so a run is repeatable; the first case of every distinct failure is written
to ``--keep`` (default: not kept) for replay.

    python benchmarks/bench_fuzz.py [--cases 10500] [--kills 40] [--seed 0] [--keep DIR] [--json]
"""
from __future__ import annotations

import argparse
import collections
import json
import logging
import os
import pathlib
import random
import re
import shutil
import signal
import subprocess
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


# --- output paths and SIGKILL ------------------------------------------------------------

TEMP_NAME = re.compile(r"^\..+\.\d+-[0-9a-f]{12}\.(tmp|old)$")   # files.tempnames


def _workdir(tmp: pathlib.Path) -> pathlib.Path:
    """A folder with the inputs the writing commands read: d.csv (train and val rows of the
    shipped SYNTHETIC data) and design.json (one piece, one patch)."""
    work = tmp / "work"
    work.mkdir(parents=True)
    lines = (DATA / "measured_synthetic.csv").read_text("utf-8").splitlines()
    head = [x for x in lines if x.startswith(("#", "sample_id"))]
    rows = [x for x in lines if x.endswith(",train")][1:7] + [x for x in lines if x.endswith(",val")][:3]
    (work / "d.csv").write_text("\n".join(head + rows) + "\n")
    design = json.loads(_design_seed())
    design["patches"] = design["patches"][:1]
    (work / "design.json").write_text(json.dumps(design, indent=1))
    return work


#: Writing commands with {OUT} for one output path, and that output's extension ("" for a
#: folder; None for a file whose extension is free: its content does not depend on it).
OUTPUT_CASES = [
    (["simulate", "--profile-csv", "{OUT}"], None),
    (["precompute", "--diameters", "30:31:1", "--fills", "0.8:0.81:0.01", "--workers", "1",
      "-o", "{OUT}"], ".npz"),
    (["precompute", "--diameters", "30:31:1", "--fills", "0.8:0.81:0.01", "--workers", "1",
      "-o", "m.npz", "--plot", "{OUT}"], ".png"),
    (["calibrate", "d.csv", "--maxiter", "1", "--popsize", "2", "--workers", "1", "-o",
      "{OUT}"], ".json"),
    (["patch", "-d", "30", "-p", "0.8", "-o", "{OUT}"], ".dst"),
    (["patch", "-d", "30", "-p", "0.8", "-o", "p.dst", "--preview", "{OUT}"], ".png"),
    (["fem-solve", "-d", "40", "-p", "0.8", "--mesh", "{OUT}"], ".vtu"),
    (["switch-force", "-d", "60", "-p", "0.8", "--csv", "{OUT}"], ".csv"),
    (["bistability-map", "--diameters", "40", "--fills", "0.8", "--png", "{OUT}"], ".png"),
    (["preview", "-d", "40", "-p", "0.8", "-o", "{OUT}"], ".png"),
    (["preview", "-d", "40", "-p", "0.8", "-o", "p.png", "--mesh", "{OUT}"], ".ply"),
    (["import", "--rectangle", "300x200", "-o", "{OUT}"], None),
    (["place", "design.json", "--piece", "front", "--at", "200,60", "-d", "30", "-p", "0.8",
      "-o", "{OUT}"], None),
    (["discover", "d.csv", "--effects", "hardening", "--json", "{OUT}"], None),
    (["validate", "d.csv", "--report", "{OUT}"], ""),
    (["fabricate", "design.json", "-o", "{OUT}"], ""),
]
BAD_OUTPUTS = ("missing folder", "file as folder", "unwritable", "a directory", "extension")


def _tree(root: pathlib.Path) -> list[str]:
    return sorted(str(p.relative_to(root)) for p in root.rglob("*"))


def _unwritable(tmp: pathlib.Path) -> pathlib.Path | None:
    folder = tmp / "read-only"
    folder.mkdir(exist_ok=True)
    folder.chmod(0o555)
    for candidate in (folder, pathlib.Path("/sys")):
        try:
            (candidate / ".probe").write_text("x")
            (candidate / ".probe").unlink()
        except OSError:
            return candidate
    return None


def output_sample(rng: random.Random, n: int, tmp: pathlib.Path) -> dict:
    """``n`` bad output paths through click's runner (see the module docstring)."""
    from click.testing import CliRunner

    from stitchswitch.cli.main import cli

    work = _workdir(tmp)
    unwritable = _unwritable(tmp)
    (work / "taken.dir").mkdir()
    (work / "taken.dir" / "keep.txt").write_text("x")
    counts, slowest, failures = collections.Counter(), 0.0, {}
    cwd = os.getcwd()
    os.chdir(work)
    try:
        for _ in range(n):
            args, ext = rng.choice(OUTPUT_CASES)
            kind = rng.choice([k for k in BAD_OUTPUTS if (k != "unwritable" or unwritable)
                               and (k != "extension" or ext)])
            ext = ext or ".out"
            bad = {"missing folder": f"missing-{rng.randrange(99)}/x{ext}",
                   "file as folder": f"d.csv/x{ext}",
                   "unwritable": f"{unwritable}/x{ext}",
                   "a directory": "taken.dir",
                   "extension": f"x{ext}.{rng.choice(['xyz', 'txt', 'gif', 'exe'])}"}[kind]
            before = _tree(work)
            signal.setitimer(signal.ITIMER_REAL, HANG_S)
            start = time.perf_counter()
            try:
                result = CliRunner().invoke(cli, [a.replace("{OUT}", bad) for a in args])
                lines = result.stderr.strip().splitlines()
                if result.exception is not None and not isinstance(result.exception, SystemExit):
                    outcome = "crash"
                    detail = f"{args[0]} {kind}: {type(result.exception).__name__}"
                elif _tree(work) != before:
                    outcome, detail = "partial", f"{args[0]} {kind}: wrote something"
                elif (result.exit_code != 2 or len(lines) != 1 or not lines[0].startswith("Error: ")
                      or bad not in lines[0] or len(lines[0]) - len(bad) >= MAX_MESSAGE):
                    outcome, detail = "message", f"{args[0]} {kind}: {result.output[:120]!r}"
                else:
                    outcome, detail = "refused", ""
            except Hang:
                outcome, detail = "hang", f"{args[0]} {kind}"
            finally:
                signal.setitimer(signal.ITIMER_REAL, 0)
            slowest = max(slowest, time.perf_counter() - start)
            counts[outcome] += 1
            if outcome != "refused":
                failures.setdefault((outcome, detail.split(":")[0]), {
                    "group": "CLI outputs", "outcome": outcome, "seed": " ".join(args[:1]),
                    "detail": detail})
    finally:
        os.chdir(cwd)
    return _row("CLI outputs", n, counts, slowest), list(failures.values())


#: name, command line (run in a fresh folder next to the inputs), its outputs, whether a
#: previous output may be in place (a folder output is replaced with --force or as a previous
#: report).
KILL_COMMANDS = [
    ("precompute --out --plot", ["precompute", "--diameters", "30:32:1", "--fills",
                                 "0.8:0.82:0.01", "--workers", "1", "-o", "m.npz", "--plot",
                                 "p.png"], ["m.npz", "p.png"]),
    ("patch -o --preview", ["patch", "-d", "40", "-p", "0.8", "-o", "p.jef", "--preview",
                            "p.png"], ["p.jef", "p.png"]),
    ("calibrate --out", ["calibrate", "../d.csv", "--maxiter", "2", "--popsize", "2", "--workers",
                         "1", "-o", "m.json"], ["m.json", "m.calibration.json"]),
    ("preview -o --mesh", ["preview", "-d", "40", "-p", "0.8", "-o", "s.png", "--mesh", "s.ply"],
     ["s.png", "s.ply"]),
    ("simulate --profile-csv", ["simulate", "--profile-csv", "prof.csv"], ["prof.csv"]),
    ("fabricate -o", ["fabricate", "../design.json", "-o", "fab", "--force"], ["fab"]),
    ("validate --report", ["validate", "../d.csv", "--report", "rep"], ["rep"]),
]
PREVIOUS = b"previous output\n"


def _complete(path: pathlib.Path, ref: pathlib.Path) -> bool:
    """``path`` holds the whole output ``ref`` of a complete run: the same bytes, or, for
    outputs that carry timings, the same structure."""
    if ref.is_dir():
        return (path.is_dir() and not path.is_symlink() and _tree(path) == _tree(ref)
                and all(_complete(path / name, ref / name) for name in _tree(ref)
                        if (ref / name).is_file()))
    if not path.is_file():
        return False
    data, want = path.read_bytes(), ref.read_bytes()
    if data == want:
        return True
    ext = path.suffix.lower()
    try:
        if ext == ".json":
            return sorted(json.loads(data)) == sorted(json.loads(want))
        if ext == ".npz":
            from stitchswitch.reduced.design_space.storage import load_map
            load_map(path)
            return True
        if ext == ".png":
            return data.startswith(b"\x89PNG") and data.endswith(b"IEND\xaeB`\x82")
        if ext in (".md", ".html", ".svg", ".csv"):
            return (data.count(b"\n") == want.count(b"\n")
                    and data.rstrip().rsplit(b"\n", 1)[-1][:8] == want.rstrip().rsplit(b"\n", 1)[-1][:8])
    except Exception:
        return False
    return False


def _state(path: pathlib.Path, ref: pathlib.Path, planted: bool) -> str:
    if not path.exists() and not path.is_symlink():
        return "absent"
    if planted and path.is_file() and path.read_bytes() == PREVIOUS:
        return "previous"
    return "complete" if _complete(path, ref) else "corrupt"


def _plant(case: pathlib.Path, outputs, ref: pathlib.Path) -> None:
    for name in outputs:
        if (ref / name).is_dir():
            shutil.copytree(ref / name, case / name)       # a previous output of the tool
        else:
            (case / name).write_bytes(PREVIOUS)


def _run(args, cwd, env, timeout):
    return subprocess.run([sys.executable, "-m", "stitchswitch", "-q", *args], cwd=cwd, env=env,
                          capture_output=True, text=True, timeout=timeout)


def kill_sample(rng: random.Random, n: int, tmp: pathlib.Path) -> tuple[dict, list]:
    """``n`` writing commands killed at random times (see the module docstring)."""
    work = _workdir(tmp / "kill")
    env = {**os.environ, "PYTHONPATH": str(ROOT / "src"), "STITCHSWITCH_CACHE": str(tmp / "cache")}
    refs, times = {}, {}
    for name, args, _ in KILL_COMMANDS:                 # one complete run of each, timed
        ref = work / f"ref-{len(refs)}"
        ref.mkdir()
        t0 = time.perf_counter()
        done = _run(args, ref, env, 600)
        if done.returncode != 0:
            raise SystemExit(f"{name} failed on clean input: {done.stderr[-300:]}")
        refs[name], times[name] = ref, time.perf_counter() - t0
    counts, slowest, failures = collections.Counter(), 0.0, {}
    for k in range(n):
        name, args, outputs = rng.choice(KILL_COMMANDS)
        case = work / f"case-{k}"
        case.mkdir()
        planted = rng.random() < 0.5
        if planted:
            _plant(case, outputs, refs[name])
        proc = subprocess.Popen([sys.executable, "-m", "stitchswitch", "-q", *args], cwd=case,
                                env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        # half the kills at any time of the run, half near its end, where the files are written
        late = rng.random() < 0.5
        time.sleep(times[name] * (rng.uniform(0.75, 1.05) if late else rng.uniform(0.0, 1.1)))
        killed = proc.poll() is None
        proc.send_signal(signal.SIGKILL)
        proc.wait()
        states = [_state(case / o, refs[name] / o, planted) for o in outputs]
        mixed = len(set(states)) > 1
        outcome, detail = ("refused" if killed else "ok"), ""
        if "corrupt" in states or mixed:
            outcome, detail = "partial", f"{name}: outputs {', '.join(states)} after the kill"
        t0 = time.perf_counter()
        try:
            again = _run(args, case, env, 300)
        except subprocess.TimeoutExpired:
            again = None
        slowest = max(slowest, time.perf_counter() - t0)
        if again is None:
            outcome, detail = "hang", f"{name}: the run after the kill took over 300 s"
        elif again.returncode != 0:
            outcome, detail = "crash", f"{name}: the run after the kill failed: {again.stderr[-160:]!r}"
        elif not all(_complete(case / o, refs[name] / o) for o in outputs):
            outcome, detail = "partial", f"{name}: incomplete outputs after the run after the kill"
        left = [p.name for p in case.rglob(".*") if TEMP_NAME.match(p.name)]
        counts["leftover"] += len(left)
        if left:
            failures.setdefault(("leftover", name), {"group": "SIGKILL", "outcome": "leftover",
                                                     "seed": name, "detail": ", ".join(left[:3])})
        counts[outcome] += 1
        if outcome not in ("ok", "refused"):
            failures.setdefault((outcome, name), {"group": "SIGKILL", "outcome": outcome,
                                                  "seed": name, "detail": detail})
        shutil.rmtree(case, ignore_errors=True)
    return _row("SIGKILL", n, counts, slowest), list(failures.values())


def _row(group, n, counts, slowest) -> dict:
    return {"group": group, "cases": n, "loaded": counts["ok"], "refused": counts["refused"],
            "crashes": counts["crash"], "bad_messages": counts["message"],
            "hangs": counts["hang"], "partial_files": counts["partial"],
            "leftover_temps": counts["leftover"], "slowest_s": slowest}


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
    ap.add_argument("--outputs", type=int, default=300, help="bad output paths (CLI outputs)")
    ap.add_argument("--kills", type=int, default=40, help="writing commands killed (SIGKILL)")
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
            rows.append(_row(name, n, counts, slowest))
        for sample, size in ((output_sample, args.outputs), (kill_sample, args.kills)):
            if size:
                row, found = sample(rng, size, tmp)
                rows.append(row)
                for f in found:
                    failures.setdefault((f["group"], f["outcome"], f["seed"]), f)
        elapsed = time.perf_counter() - t0
    total = {k: sum(r[k] for r in rows) for k in ("cases", "loaded", "refused", "crashes",
                                                   "bad_messages", "hangs", "partial_files",
                                                   "leftover_temps")}
    target = total["cases"] >= 10_000 and not any(
        total[k] for k in ("crashes", "bad_messages", "hangs", "partial_files", "leftover_temps"))
    result = {"seed": args.seed, "rows": rows, "total": total, "elapsed_s": elapsed,
              "failures": list(failures.values()), "target_met": target}
    if args.json:
        print(json.dumps(result, indent=1))
        return 0
    head = (f"{'group':<15}{'cases':>7}{'loaded':>8}{'refused':>9}{'crashes':>9}"
            f"{'bad msg':>9}{'hangs':>7}{'partial':>9}{'temps left':>12}{'slowest s':>11}")
    print(head)
    print("-" * len(head))
    for r in rows + [dict(group="all", slowest_s=max(r["slowest_s"] for r in rows), **total)]:
        print(f"{r['group']:<15}{r['cases']:>7}{r['loaded']:>8}{r['refused']:>9}"
              f"{r['crashes']:>9}{r['bad_messages']:>9}{r['hangs']:>7}{r['partial_files']:>9}"
              f"{r['leftover_temps']:>12}{r['slowest_s']:>11.2f}")
    print("SIGKILL: loaded = finished before the kill, refused = killed while running")
    print(f"{elapsed:.0f} s in all")
    for f in failures.values():
        print(f"  {f['group']}: {f['outcome']} ({f['seed']}): {f['detail']}")
    print(f"target 0 crashes / 0 bad messages / 0 hangs / 0 partial files / 0 temps left on "
          f">= 10,000 cases: "
          f"{'PASS' if target else 'FAIL'}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
