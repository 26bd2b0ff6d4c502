"""Examples as tests: every ``console`` block of docs/guide.md runs, top to bottom, in one fresh
folder, as a user would type it, and so does every README.md block that shows output. A ``$``
line is a command (``>`` lines continue it); the lines after it are its expected output, each of
which must appear in the real output in order (times such as ``0.03 s`` are masked; ``...``
skips lines). Commands must exit 0 unless the line ends in ``# exit N``."""
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from helpers import EXTERNAL

DOCS = Path(__file__).resolve().parents[1] / "docs"
GUIDE = DOCS / "guide.md"
README = DOCS.parent / "README.md"
TIME = re.compile(r"\d+(\.\d+)? (ms|s)\b")


def blocks(text: str):
    return re.findall(r"```console\n(.*?)```", text, flags=re.S)


def commands(block: str):
    """(command, expected output lines, expected exit code) of one block."""
    out = []
    for line in block.splitlines():
        if line.startswith("$ "):
            out.append([line[2:], [], 0])
        elif line.startswith("> ") or line == ">":
            out[-1][0] += "\n" + line[2:]
        elif out:
            out[-1][1].append(line)
    for entry in out:
        m = re.search(r"#\s*exit (\d+)\s*$", entry[0].splitlines()[0])
        if m:
            entry[2] = int(m.group(1))
    return [tuple(e) for e in out]


def shell(command: str) -> str:
    if command.startswith("stitchswitch "):
        command = f'"{sys.executable}" -m stitchswitch ' + command[len("stitchswitch "):]
    return command


def normal(line: str) -> str:
    return TIME.sub("<t>", line.rstrip())


def assert_output(expected, actual: str, command: str):
    lines = [normal(x) for x in actual.splitlines()]
    pos = 0
    for want in (normal(x) for x in expected):
        if not want or want == "...":
            continue
        try:
            pos = lines.index(want, pos) + 1
        except ValueError:
            raise AssertionError(f"{command!r}: expected line {want!r} not in output:\n{actual}") from None


def test_guide_has_runnable_examples():
    all_commands = [c for b in blocks(GUIDE.read_text()) for c in commands(b)]
    assert len(all_commands) >= 12
    assert all(c[0].split()[0] in ("stitchswitch", "cat") for c in all_commands)


def test_guide_images_exist():
    for name in re.findall(r"\]\((img/[^)]+)\)", GUIDE.read_text()):
        assert (DOCS / name).is_file(), name


@pytest.mark.slow
def test_guide_examples_run(tmp_path):
    # the guide's garment pattern, as the reader downloads it (tests/data/external/README.md)
    shutil.copyfile(EXTERNAL / "dxf" / "WM_LOOSE_SHAPE_TANK_AAMA.DXF", tmp_path / "tank.dxf")
    for block in blocks(GUIDE.read_text()):
        for command, expected, code in commands(block):
            r = subprocess.run(["bash", "-c", shell(command)], cwd=tmp_path, capture_output=True,
                               text=True, timeout=900)
            assert r.returncode == code, f"{command!r} exited {r.returncode}:\n{r.stdout}\n{r.stderr}"
            assert_output(expected, r.stdout, command)
    assert (tmp_path / "pocket-demo" / "summary.html").is_file()
    assert (tmp_path / "fabrication" / "hoop01.jef").is_file()
    assert (tmp_path / "my-material.json").is_file()
    assert (tmp_path / "tank-fabrication" / "hoop02.jef").is_file()
    assert (tmp_path / "tank-layout.png").is_file()


def test_readme_examples_with_output_run(tmp_path):
    """The README's console blocks that show output (the others only list commands on files
    the reader brings) print what the README says."""
    shown = [c for b in blocks(README.read_text()) for c in commands(b) if c[1]]
    assert shown
    for command, expected, code in shown:
        r = subprocess.run(["bash", "-c", shell(command)], cwd=tmp_path, capture_output=True,
                           text=True, timeout=300)
        assert r.returncode == code, f"{command!r} exited {r.returncode}:\n{r.stdout}\n{r.stderr}"
        assert_output(expected, r.stdout, command)


def test_output_matching_can_fail():
    assert_output(["h  1.0 mm", "...", "time  0.5 s"], "x\nh  1.0 mm\ny\ntime  7.25 s\n", "c")
    with pytest.raises(AssertionError, match="expected line"):
        assert_output(["h  1.1 mm"], "h  1.0 mm\n", "c")
    with pytest.raises(AssertionError):
        assert_output(["b", "a"], "a\nb\n", "c")          # order matters
    assert commands("$ stitchswitch check d.json  # exit 1\nrow\n$ cat > f <<'EOF'\n> x\n> EOF\n") == [
        ("stitchswitch check d.json  # exit 1", ["row"], 1), ("cat > f <<'EOF'\nx\nEOF", [], 0)]
