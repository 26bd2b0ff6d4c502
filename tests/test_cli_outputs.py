"""Output paths of every command: checked before any work (one ``Error:`` line naming the
user's path, exit code 2, nothing written), and the files of one command written as one unit."""
import os
import re

import click
import pytest
from click.testing import CliRunner

from stitchswitch.cli import options
from stitchswitch.cli.main import COMMANDS, cli

from helpers import unwritable_dir

MEASURED = """# source: synthetic (test rows)
sample_id,d_mm,fill,h_mm,r_a_mm,z_a_mm,r_b_mm,z_b_mm,split
a,40,0.8,11.73,14.60,5.79,14.68,5.70,train
b,50,0.7,14.62,20.71,6.90,20.73,6.80,val
"""

#: Names of the file options a command writes to.
OUTPUT_PARAMS = {"out", "output", "plot", "preview_path", "mesh", "mesh_path", "csv_path",
                 "profile_csv"}
#: Commands being rewritten elsewhere, whose output options still have to use OutputFile
#: (``cli/reference``): listed here until then.
PENDING = set()


def test_every_output_file_option_is_checked_at_parse_time():
    ctx = click.Context(cli)
    unchecked = []
    for name in COMMANDS:
        command = cli.get_command(ctx, name)
        for param in command.params:
            if param.name in OUTPUT_PARAMS and not isinstance(param.type, options.OutputFile):
                unchecked.append((name, param.name))
    assert set(unchecked) <= PENDING, unchecked


#: (command line with {OUT} for the output, a second output given too, the extension)
CASES = {
    "simulate --profile-csv": (["simulate", "--profile-csv", "{OUT}"], ".csv"),
    "precompute --out": (["precompute", "--diameters", "30:40:10", "--fills", "0.8:0.9:0.1",
                          "--workers", "1", "-o", "{OUT}"], ".npz"),
    "precompute --plot": (["precompute", "--diameters", "30:40:10", "--fills", "0.8:0.9:0.1",
                           "--workers", "1", "-o", "m.npz", "--plot", "{OUT}"], ".png"),
    "calibrate --out": (["calibrate", "d.csv", "--maxiter", "1", "--popsize", "2", "--workers",
                         "1", "-o", "{OUT}"], ".json"),
    "patch -o": (["patch", "-d", "30", "-p", "0.8", "-o", "{OUT}"], ".dst"),
    "patch --preview": (["patch", "-d", "30", "-p", "0.8", "-o", "p.dst", "--preview", "{OUT}"],
                        ".png"),
    "import -o": (["import", "--rectangle", "300x200", "-o", "{OUT}"], ".json"),
    "place -o": (["place", "design.json", "--piece", "rectangle", "--at", "150,100", "-d", "30",
                  "-p", "0.8", "-o", "{OUT}"], ".json"),
    "preview -o": (["preview", "-d", "40", "-p", "0.8", "-o", "{OUT}"], ".png"),
    "preview --mesh": (["preview", "-d", "40", "-p", "0.8", "-o", "p.png", "--mesh", "{OUT}"],
                       ".ply"),
    "discover --json": (["discover", "d.csv", "--json", "{OUT}"], ".json"),
    "validate --report": (["validate", "d.csv", "--report", "{OUT}"], ""),
    "fabricate -o": (["fabricate", "design.json", "-o", "{OUT}"], ""),
    "demo -o": (["demo", "-o", "{OUT}"], ""),
    "fem-solve --mesh": (["fem-solve", "-d", "40", "-p", "0.8", "--mesh", "{OUT}"], ".vtu"),
    "switch-force --csv": (["switch-force", "-d", "60", "-p", "0.8", "--csv", "{OUT}"], ".csv"),
    "switch-force --plot": (["switch-force", "-d", "60", "-p", "0.8", "--csv", "c.csv", "--plot",
                             "{OUT}"], ".png"),
    "fem-check --report": (["fem-check", "--designs", "40,0.8", "--report", "{OUT}"], ""),
    "bistability-map --png": (["bistability-map", "--diameters", "40", "--fills", "0.8", "--png",
                               "{OUT}"], ".png"),
}


@pytest.fixture
def workdir(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "d.csv").write_text(MEASURED)
    assert CliRunner().invoke(cli, ["import", "--rectangle", "300x200", "-o",
                                    "design.json"]).exit_code == 0
    return tmp_path


def _bad_path(kind, ext, tmp_path):
    if kind == "missing directory":
        return os.path.join("missingdir", "x" + ext), "does not exist"
    if kind == "under a file":
        return os.path.join("d.csv", "x" + ext), "is not a directory"
    if kind == "unwritable":
        return os.path.join(str(unwritable_dir(tmp_path)), "x" + ext), "cannot write in the directory"
    (tmp_path / ("taken" + ext)).mkdir()
    return "taken" + ext, ("is a directory" if ext else "is not empty")


@pytest.mark.parametrize("case", sorted(CASES))
@pytest.mark.parametrize("kind", ["missing directory", "under a file", "unwritable",
                                  "a directory"])
def test_a_bad_output_path_is_one_error_before_any_work(workdir, case, kind, monkeypatch):
    args, ext = CASES[case]
    if kind == "a directory" and not ext:
        (workdir / "taken").mkdir()
        (workdir / "taken" / "keep.txt").write_text("x")
        bad, needle = "taken", "is not empty|not from this tool"
    else:
        bad, needle = _bad_path(kind, ext, workdir)
    before = sorted(os.listdir(workdir))
    result = CliRunner().invoke(cli, [a.replace("{OUT}", bad) for a in args])
    assert result.exit_code == 2, result.output
    lines = result.stderr.splitlines()
    assert len(lines) == 1 and lines[0].startswith("Error: "), result.stderr
    assert repr(bad)[1:-1] in lines[0] and re.search(needle, lines[0])
    assert ".tmp" not in lines[0] and "Traceback" not in result.output
    assert sorted(os.listdir(workdir)) == before


@pytest.mark.parametrize("args, bad", [
    (["precompute", "-o", "m.xyz"], "unknown extension '.xyz'; use .npz"),
    (["precompute", "-o", "m.npz", "--plot", "p.jpg"], "unknown extension '.jpg'; use .png"),
    (["patch", "-d", "30", "-p", "0.8", "-o", "p.dst", "--preview", "p.gif"], "'.gif'"),
    (["preview", "-d", "40", "-p", "0.8", "-o", "p.png", "--mesh", "m.xyz"], "'.xyz'"),
    (["calibrate", "d.csv", "-o", "m.txt"], "use .json"),
    (["import", "--rectangle", "300x200", "--name", "panel", "-o", "d.yaml"], "use .json"),
    (["simulate", "-d", "40", "-p", "0.8", "--profile-csv", "p.txt"], "use .csv"),
    (["discover", "--demo", "--json", "r.txt"], "use .json"),
    (["patch", "-d", "30", "-p", "0.8", "-o", "p.png", "--format", "dst", "--preview", "p.png"],
     "the same file as --output"),
])
def test_a_wrong_extension_or_a_repeated_file_is_refused_first(workdir, args, bad):
    before = sorted(os.listdir(workdir))
    result = CliRunner().invoke(cli, args)
    assert result.exit_code == 2 and bad in result.stderr, result.output
    assert len(result.stderr.splitlines()) == 1
    assert sorted(os.listdir(workdir)) == before


def test_the_check_comes_before_the_compute(workdir, monkeypatch):
    from stitchswitch.reduced.design_space import precompute

    def build(*args, **kwargs):
        raise AssertionError("computed before the output check")
    monkeypatch.setattr(precompute, "build", build)
    result = CliRunner().invoke(cli, ["precompute", "-o", "m.npz", "--plot",
                                      "missingdir/p.png"])
    assert result.exit_code == 2 and "missingdir/p.png" in result.stderr


def _fail_second_output(monkeypatch, module, name):
    def boom(*args, **kwargs):
        raise OSError(28, "No space left on device")
    monkeypatch.setattr(module, name, boom)


@pytest.mark.parametrize("existing", [False, True])
def test_precompute_writes_map_and_plot_together(workdir, monkeypatch, existing):
    from stitchswitch.reduced.design_space import heatmap

    if existing:
        (workdir / "m.npz").write_bytes(b"old map")
    _fail_second_output(monkeypatch, heatmap, "plot_height_map")
    result = CliRunner().invoke(cli, ["precompute", "--diameters", "30:40:10", "--fills",
                                      "0.8:0.9:0.1", "--workers", "1", "-o", "m.npz",
                                      "--plot", "p.png"])
    assert result.exit_code == 2, result.output
    assert result.stderr.splitlines()[-1] == ("Error: --plot 'p.png': cannot be written (No "
                                              "space left on device)")
    assert not (workdir / "p.png").exists()
    if existing:
        assert (workdir / "m.npz").read_bytes() == b"old map"
    else:
        assert not (workdir / "m.npz").exists()
    assert not [n for n in os.listdir(workdir) if n.startswith(".")]


def test_patch_writes_file_and_preview_together(workdir, monkeypatch):
    from stitchswitch.layout.embroidery import stitch_preview

    _fail_second_output(monkeypatch, stitch_preview, "write_preview")
    result = CliRunner().invoke(cli, ["patch", "-d", "30", "-p", "0.8", "-o", "p.dst",
                                      "--preview", "p.png"])
    assert result.exit_code == 2 and "--preview 'p.png'" in result.stderr, result.output
    assert not (workdir / "p.dst").exists() and not (workdir / "p.png").exists()


def test_preview_writes_image_and_mesh_together(workdir, monkeypatch):
    from stitchswitch.files import atomic

    real = atomic.atomic_write_bytes

    def fail_png(path, data):
        if str(path).endswith(".png"):
            raise OSError(28, "No space left on device", str(path))
        return real(path, data)
    monkeypatch.setattr(atomic, "atomic_write_bytes", fail_png)
    result = CliRunner().invoke(cli, ["preview", "-d", "40", "-p", "0.8", "-o", "p.png",
                                      "--mesh", "m.ply"])
    assert result.exit_code == 2 and "--output 'p.png'" in result.stderr, result.output
    assert not (workdir / "m.ply").exists() and not (workdir / "p.png").exists()
