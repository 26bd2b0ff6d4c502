"""stderr on clean input: library logs (ezdxf's recover messages) and Python warnings (numpy's
RuntimeWarning) go to the package's logger at info level, shown with -v only; -q hides
progress and warnings."""
import os
import subprocess
import sys

from helpers import EXTERNAL

CLO = EXTERNAL / "dxf" / "clo-box_R10.dxf"         # CLO writes floats in integer fields


def run(*args, cwd):
    env = {**os.environ, "PYTHONPATH": os.pathsep.join(sys.path), "PYTHONWARNINGS": "default"}
    return subprocess.run([sys.executable, *args], capture_output=True, text=True, cwd=cwd,
                          env=env, timeout=300)


def test_ezdxf_recover_lines_are_shown_with_verbose_only(tmp_path):
    default = run("-m", "stitchswitch", "import", str(CLO), "-o", "a.json", cwd=tmp_path)
    assert default.returncode == 0, default.stderr
    lines = default.stderr.splitlines()
    # the repairs, and the box's 3 x 2 m, implausible for a garment piece
    assert len(lines) == 2 and all(line.startswith("Warning: ") for line in lines)
    assert "repaired" in lines[0] and "implausibly large" in lines[1]
    assert not any(line.startswith("recovered") for line in default.stderr.splitlines())
    quiet = run("-m", "stitchswitch", "-q", "import", str(CLO), "-o", "b.json", cwd=tmp_path)
    assert quiet.returncode == 0 and quiet.stderr == ""
    verbose = run("-m", "stitchswitch", "-v", "import", str(CLO), "-o", "c.json", cwd=tmp_path)
    assert "Info: ezdxf: recovered invalid integer value" in verbose.stderr
    assert (tmp_path / "a.json").read_bytes() == (tmp_path / "c.json").read_bytes()


CODE = """
import sys, numpy as np
from stitchswitch.cli.main import configure_logging
configure_logging(int(sys.argv[1]))
np.log(np.zeros(2))
print("done")
"""


def test_numpy_warnings_go_to_the_logger(tmp_path):
    default = run("-c", CODE, "0", cwd=tmp_path)
    assert default.returncode == 0 and default.stdout == "done\n" and default.stderr == ""
    verbose = run("-c", CODE, "1", cwd=tmp_path)
    (line,) = verbose.stderr.splitlines()
    assert line.startswith("Info: py.warnings: ") and "RuntimeWarning: divide by zero" in line


def test_quiet_hides_progress(tmp_path):
    args = ("-m", "stitchswitch", "{q}", "precompute", "--diameters", "30:31:1", "--fills",
            "0.8:0.81:0.01", "--workers", "1", "-o", "m.npz")
    loud = run(*[a.replace("{q}", "-v") for a in args], cwd=tmp_path)
    assert loud.returncode == 0 and "solving 2 x 2 designs" in loud.stderr
    quiet = run(*[a.replace("{q}", "-q") for a in args], cwd=tmp_path)
    assert quiet.returncode == 0 and quiet.stderr == "" and "wrote m.npz" in quiet.stdout
