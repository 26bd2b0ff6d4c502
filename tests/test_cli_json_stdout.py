"""With ``--json`` stdout carries the JSON and nothing else, even where native libraries print:
HiGHS writes a banner with C stdio on every solve (``stitchswitch.native_output``)."""
import json
import subprocess
import sys


def run(*args):
    return subprocess.run([sys.executable, "-m", "stitchswitch", *args], capture_output=True, text=True,
                          timeout=300)


def test_inverse_json_is_alone_on_stdout():
    result = run("inverse", "--height", "12", "--count", "1", "--json")
    assert result.returncode == 0, result.stderr
    out = json.loads(result.stdout)
    assert out["candidates"] and "Running HiGHS" not in result.stdout


def test_the_banner_goes_to_the_log_with_verbose():
    result = run("-v", "inverse", "--height", "12", "--count", "1", "--json")
    assert result.returncode == 0, result.stderr
    json.loads(result.stdout)
    assert "Running HiGHS" in result.stderr
