"""Every command that has ``--json`` prints JSON alone on stdout, and with ``-q`` nothing at all
on stderr on clean input (no progress, no library log, no numpy warning). The commands are
enumerated from the click group, so a new command with ``--json`` fails here until it is given
a small input below."""
import json
import os
import subprocess
import sys

import click
import pytest

from stitchswitch.cli.main import COMMANDS, cli

MEASURED = os.path.join(os.path.dirname(__file__), "..", "src", "stitchswitch", "data",
                        "measured_synthetic.csv")

#: Small, fast arguments per command (files are made by the ``workdir`` fixture).
ARGS = {
    "simulate": ["simulate", "-d", "40", "-p", "0.8"],
    "precompute": ["precompute", "--diameters", "30:40:10", "--fills", "0.8:0.9:0.1",
                   "--workers", "1", "-o", "m.npz"],
    "inverse": ["inverse", "--height", "12", "--count", "1"],
    "force": ["force", "-d", "40", "-p", "0.8"],
    "validate": ["validate", "d.csv", "--report", "report"],
    "calibrate": ["calibrate", "d.csv", "--maxiter", "1", "--popsize", "2", "--workers", "1",
                  "-o", "material.json"],
    "sensitivity": ["sensitivity", "--workers", "1"],
    "discover": ["discover", "d.csv", "--effects", "hardening", "--folds", "2", "--workers", "1"],
    "fem-check": ["fem-check", "--designs", "40,0.8"],
    "switch-force": ["switch-force", "-d", "90", "-p", "0.6", "--elements", "16", "--steps", "12"],
    "bistability-map": ["bistability-map", "--diameters", "40,60", "--fills", "0.8"],
    "fem-solve": ["fem-solve", "-d", "40", "-p", "0.8", "--elements", "8"],
    "check": ["check", "design.json"],
    "inspect": ["inspect", os.path.join(os.path.dirname(__file__), "data", "external",
                                        "embroidery", "Star.JEF")],
}
#: Exit codes other than 0 that a clean run may have (check: 1 when the design has violations).
EXIT = {"check": (0, 1), "fem-check": (0, 1)}       # 1: a finding (violations, outside the budget)
SLOW = {"fem-check", "discover", "bistability-map"}       # over 20 s on the 2-core test machine


def json_commands() -> list[str]:
    ctx = click.Context(cli)
    return [name for name in COMMANDS
            if any("--json" in p.opts for p in cli.get_command(ctx, name).params)]


def test_every_json_command_is_covered():
    assert sorted(json_commands()) == sorted(ARGS)


@pytest.fixture(scope="module")
def workdir(tmp_path_factory):
    root = tmp_path_factory.mktemp("json")
    lines = open(MEASURED, encoding="utf-8").read().splitlines()
    head = [x for x in lines if x.startswith("#") or x.startswith("sample_id")]
    train = [x for x in lines if x.endswith(",train")][1:7]
    val = [x for x in lines if x.endswith(",val")][:3]
    (root / "d.csv").write_text("\n".join(head + train + val) + "\n")
    env = _env(root)
    for args in (["import", "--rectangle", "300x200", "-o", "design.json"],
                 ["place", "design.json", "--piece", "rectangle", "--at", "150,100", "-d", "30",
                  "-p", "0.8"]):
        subprocess.run([sys.executable, "-m", "stitchswitch", *args], cwd=root, env=env,
                       check=True, capture_output=True)
    return root


def _env(root):
    return {**os.environ, "PYTHONPATH": os.pathsep.join(sys.path),
            "STITCHSWITCH_CACHE": str(root / "cache"), "PYTHONWARNINGS": "default"}


@pytest.mark.parametrize("name", [pytest.param(n, marks=pytest.mark.slow) if n in SLOW else n
                                  for n in sorted(ARGS)])
def test_json_alone_on_stdout_and_quiet_stderr(workdir, name):
    args = list(ARGS[name])
    json_flag = ["--json"]
    result = subprocess.run([sys.executable, "-m", "stitchswitch", "-q", *args, *json_flag],
                            cwd=workdir, env=_env(workdir), capture_output=True, text=True,
                            timeout=600)
    assert result.returncode in EXIT.get(name, (0,)), result.stderr
    value = json.loads(result.stdout)
    assert isinstance(value, dict) and value
    assert result.stderr == "", result.stderr
