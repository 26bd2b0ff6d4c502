"""stitchswitch.files.atomic: complete file or nothing, and never a stray temporary file."""
import os

import pytest

from stitchswitch.files import atomic
from stitchswitch.files.atomic import atomic_write_bytes, atomic_write_text


def test_writes_and_overwrites(tmp_path):
    target = tmp_path / "out.txt"
    atomic_write_text(target, "first\n")
    atomic_write_text(target, "second é\r\n")
    assert target.read_bytes() == "second é\r\n".encode("utf-8")
    atomic_write_bytes(str(target), b"\x00\x01")
    assert target.read_bytes() == b"\x00\x01"
    assert os.listdir(tmp_path) == ["out.txt"]


def test_new_file_respects_umask(tmp_path):
    mask = os.umask(0o022)
    try:
        atomic_write_text(tmp_path / "f", "x")
    finally:
        os.umask(mask)
    assert (tmp_path / "f").stat().st_mode & 0o777 == 0o644


@pytest.mark.parametrize("exc", [OSError("disk full"), KeyboardInterrupt()])
def test_failed_write_leaves_no_file_and_no_temp(tmp_path, monkeypatch, exc):
    def fail(fd):
        raise exc
    monkeypatch.setattr(atomic.os, "fsync", fail)
    with pytest.raises(type(exc)):
        atomic_write_text(tmp_path / "out.csv", "data\n")
    assert os.listdir(tmp_path) == []


def test_failed_write_keeps_the_old_file(tmp_path, monkeypatch):
    target = tmp_path / "out.csv"
    target.write_text("old\n")

    def fail(src, dst):
        raise OSError("replace failed")
    monkeypatch.setattr(atomic.os, "replace", fail)
    with pytest.raises(OSError, match="replace failed"):
        atomic_write_text(target, "new\n")
    assert target.read_text() == "old\n"
    assert os.listdir(tmp_path) == ["out.csv"]


def test_bad_data_leaves_nothing(tmp_path):
    with pytest.raises(TypeError):
        atomic_write_bytes(tmp_path / "out.bin", "not bytes")
    assert os.listdir(tmp_path) == []


def test_missing_directory_raises_and_creates_nothing(tmp_path):
    with pytest.raises(FileNotFoundError):
        atomic_write_text(tmp_path / "no" / "out.txt", "x")
    assert os.listdir(tmp_path) == []


def test_target_is_a_directory(tmp_path):
    (tmp_path / "d").mkdir()
    with pytest.raises(OSError):
        atomic_write_text(tmp_path / "d", "x")
    assert os.listdir(tmp_path) == ["d"]
    assert os.listdir(tmp_path / "d") == []


def test_a_killed_writers_temporary_file_is_removed_by_the_next_write(tmp_path):
    import subprocess
    import sys

    proc = subprocess.Popen([sys.executable, "-c", "pass"])
    proc.wait()
    stale = tmp_path / f".out.csv.{proc.pid}-0123456789ab.tmp"
    stale.write_text("half")
    alive = tmp_path / f".out.csv.{os.getpid()}-0123456789ab.tmp"
    alive.write_text("being written")
    foreign = tmp_path / ".out.csv.mine.tmp"
    foreign.write_text("a user's file")
    atomic_write_text(tmp_path / "out.csv", "x\n")
    assert sorted(os.listdir(tmp_path)) == sorted(["out.csv", alive.name, foreign.name])


def test_the_temporary_file_is_named_with_the_writers_pid(tmp_path, monkeypatch):
    seen = []
    real = atomic.os.replace
    monkeypatch.setattr(atomic.os, "replace", lambda src, dst: (seen.append(src), real(src, dst)))
    atomic_write_text(tmp_path / "f.txt", "x")
    assert os.path.basename(seen[0]).startswith(f".f.txt.{os.getpid()}-")
