"""Output directories (``files.outdir``): a temporary directory left by a killed writer is
removed by the next write to the same target, one of a running writer is not."""
import os
import subprocess
import sys

from stitchswitch.files.outdir import building, remove_stale, write_outdir


def _dead_pid() -> int:
    proc = subprocess.Popen([sys.executable, "-c", "pass"])
    proc.wait()
    return proc.pid


def test_a_killed_writers_temporary_directory_is_removed_by_the_next_write(tmp_path):
    out = tmp_path / "report"
    stale = tmp_path / f".report.{_dead_pid()}-0123456789ab.tmp"
    stale.mkdir()
    (stale / "half.txt").write_text("half-written")
    write_outdir(out, {"a.txt": b"x"})
    assert not stale.exists()
    assert (out / "a.txt").read_bytes() == b"x"
    assert [p.name for p in tmp_path.iterdir()] == ["report"]


def test_a_running_writers_and_foreign_directories_are_kept(tmp_path):
    out = tmp_path / "report"
    alive = tmp_path / f".report.{os.getpid()}-0123456789ab.tmp"
    foreign = [tmp_path / ".report.notours.tmp", tmp_path / ".other.123-0123456789ab.tmp",
               tmp_path / f".report.{_dead_pid()}-short.tmp"]
    for d in [alive, *foreign]:
        d.mkdir()
    assert remove_stale(out) == []
    assert all(d.is_dir() for d in [alive, *foreign])


def test_the_temporary_directory_is_named_with_the_writers_pid(tmp_path):
    with building(tmp_path / "out") as tmp:
        assert tmp.name.startswith(f".out.{os.getpid()}-") and tmp.name.endswith(".tmp")
