"""Output files (``files.outputs``): refused before any work with one error naming the user's
path; the files of one command replace their targets together or not at all."""
import os
import subprocess
import sys

import pytest

from stitchswitch.errors import InvalidInputError
from stitchswitch.files import outputs
from stitchswitch.files.atomic import atomic_write_text
from stitchswitch.files.outputs import check_distinct, check_output_file, together

from helpers import unwritable_dir


def test_a_writable_path_passes_and_leaves_nothing(tmp_path):
    assert check_output_file(tmp_path / "m.npz", (".npz",)) == tmp_path / "m.npz"
    assert os.listdir(tmp_path) == []


@pytest.mark.parametrize("case, needle", [
    ("missing", "does not exist"), ("directory", "is a directory"), ("under a file", "is not a directory"),
    ("extension", "unknown extension '.xyz'"), ("empty", "the path is empty"),
    ("unwritable", "cannot write in the directory"),
])
def test_bad_output_paths_are_refused(tmp_path, case, needle):
    (tmp_path / "d").mkdir()
    (tmp_path / "f").write_text("x")
    path = {"missing": tmp_path / "nope" / "m.npz", "directory": tmp_path / "d",
            "under a file": tmp_path / "f" / "m.npz", "extension": tmp_path / "m.xyz",
            "empty": "", "unwritable": None}[case]
    if case == "unwritable":
        path = os.path.join(unwritable_dir(tmp_path), "m.npz")
    before = sorted(os.listdir(tmp_path))
    with pytest.raises(InvalidInputError, match=needle) as info:
        check_output_file(path, (".npz",), "--out")
    assert str(info.value).startswith("--out") and len(str(info.value)) < 300
    if case != "empty":
        assert os.fspath(path) in str(info.value)
    assert sorted(os.listdir(tmp_path)) == before


def test_two_outputs_naming_one_file_are_refused(tmp_path):
    with pytest.raises(InvalidInputError, match="--plot .*the same file as --out"):
        check_distinct({"--out": tmp_path / "a.png", "--plot": str(tmp_path / "x" / ".." / "a.png")})
    check_distinct({"--out": tmp_path / "a.png", "--plot": None})


def _write_all(targets, fail_at=None):
    with together(targets) as tmp:
        for i, (what, path) in enumerate(tmp.items()):
            if i == fail_at:
                raise RuntimeError("the plot failed")
            atomic_write_text(path, f"new {what}\n")


def test_all_files_are_written_together(tmp_path):
    a, b = tmp_path / "m.npz", tmp_path / "p.png"
    _write_all({"--out": a, "--plot": b, "--csv": None})
    assert a.read_text() == "new --out\n" and b.read_text() == "new --plot\n"
    assert sorted(os.listdir(tmp_path)) == ["m.npz", "p.png"]


@pytest.mark.parametrize("existing", [False, True])
def test_a_failure_in_the_block_leaves_every_target_as_it_was(tmp_path, existing):
    a, b = tmp_path / "m.npz", tmp_path / "p.png"
    if existing:
        a.write_text("old a\n")
        b.write_text("old b\n")
    with pytest.raises(RuntimeError):
        _write_all({"--out": a, "--plot": b}, fail_at=1)
    expect = ["m.npz", "p.png"] if existing else []
    assert sorted(os.listdir(tmp_path)) == expect
    if existing:
        assert a.read_text() == "old a\n" and b.read_text() == "old b\n"


def test_a_failing_move_puts_back_the_files_already_replaced(tmp_path, monkeypatch):
    a, b = tmp_path / "m.npz", tmp_path / "p.png"
    a.write_text("old a\n")
    real = os.replace
    calls = []

    def flaky(src, dst):
        calls.append(dst)
        if os.fspath(dst) == os.fspath(b):
            raise OSError(28, "No space left on device", os.fspath(src))
        return real(src, dst)
    monkeypatch.setattr(outputs.os, "replace", flaky)
    with pytest.raises(InvalidInputError) as info:
        _write_all({"--out": a, "--plot": b})
    message = str(info.value)
    assert message.startswith(f"--plot {str(b)!r}: cannot be written (No space left on device)")
    assert ".tmp" not in message
    assert a.read_text() == "old a\n" and sorted(os.listdir(tmp_path)) == ["m.npz"]


def test_an_oserror_of_a_writer_names_the_users_path(tmp_path):
    target = tmp_path / "p.png"
    with pytest.raises(InvalidInputError) as info:
        with together({"--plot": target}) as tmp:
            raise OSError(28, "No space left on device", os.fspath(tmp["--plot"]))
    assert str(info.value) == f"--plot {str(target)!r}: cannot be written (No space left on device)"
    assert os.listdir(tmp_path) == []


def test_a_killed_writers_temporaries_are_removed_by_the_next_write(tmp_path):
    code = ("import os, sys\n"
            "from stitchswitch.files.outputs import together\n"
            "with together({'--out': sys.argv[1], '--plot': sys.argv[2]}) as tmp:\n"
            "    open(tmp['--out'], 'w').write('half')\n"
            "    os.kill(os.getpid(), 9)\n")
    a, b = tmp_path / "m.npz", tmp_path / "p.png"
    env = {**os.environ, "PYTHONPATH": os.pathsep.join(sys.path)}
    proc = subprocess.run([sys.executable, "-c", code, str(a), str(b)], env=env)
    assert proc.returncode == -9
    left = sorted(os.listdir(tmp_path))
    assert len(left) == 2 and all(n.startswith((".m.npz.", ".p.png.")) for n in left)
    _write_all({"--out": a, "--plot": b})
    assert sorted(os.listdir(tmp_path)) == ["m.npz", "p.png"]
