"""The switch-force plot and CSV are drawn and written by the library
(``fem_reference/snap/path_plot.py``, ``path_csv.py``), atomically, and are byte-identical for
the same curve: equal to the files the CLI drew before the drawing moved
(tests/data/switch_force, SYNTHETIC curve, provenance in make_golden.py), on every call, and
what ``stitchswitch switch-force`` writes."""
import os
import pathlib

import matplotlib
import pytest
from click.testing import CliRunner

from stitchswitch.cli.main import cli
from stitchswitch.fem_reference.snap import path as snap_path
from stitchswitch.fem_reference.snap import path_plot, states
from stitchswitch.fem_reference.snap.path_csv import curve_csv, write_curve_csv
from switch_force_curve import synthetic_curve

DATA = pathlib.Path(__file__).parent / "data" / "switch_force"
#: the matplotlib the golden PNG was drawn with: another version may draw other pixels
GOLDEN_MATPLOTLIB = "3.11.2"


def test_png_is_the_golden_file_and_the_same_on_every_call():
    curve = synthetic_curve()
    png = path_plot.curve_png(curve, "bistable")
    assert png[:8] == b"\x89PNG\r\n\x1a\n" and b"Software" not in png
    assert path_plot.curve_png(curve, "bistable") == png
    assert path_plot.curve_png(curve, "spring-back") != png        # the title is drawn
    if matplotlib.__version__ != GOLDEN_MATPLOTLIB:
        pytest.skip(f"golden PNG drawn with matplotlib {GOLDEN_MATPLOTLIB}, "
                    f"not {matplotlib.__version__}")
    assert png == (DATA / "curve.png").read_bytes()


def test_csv_is_the_golden_file(tmp_path):
    curve = synthetic_curve()
    assert curve_csv(curve, 200.0) == (DATA / "curve.csv").read_text()
    write_curve_csv(tmp_path / "c.csv", curve, 200.0)
    assert (tmp_path / "c.csv").read_bytes() == (DATA / "curve.csv").read_bytes()
    assert os.listdir(tmp_path) == ["c.csv"]                        # no temporary left


def test_png_is_written_with_the_atomic_helper(tmp_path, monkeypatch):
    calls = []
    monkeypatch.setattr(path_plot, "atomic_write_bytes", lambda p, data: calls.append((p, data)))
    path_plot.write_curve_png(tmp_path / "c.png", synthetic_curve(), "bistable")
    assert calls == [(tmp_path / "c.png", path_plot.curve_png(synthetic_curve(), "bistable"))]
    assert not os.listdir(tmp_path)


def test_cli_writes_the_librarys_bytes(tmp_path, monkeypatch):
    curve = synthetic_curve()
    monkeypatch.setattr(snap_path, "switching_path", lambda *a, **k: curve)
    monkeypatch.setattr(states, "bistability", lambda *a, **k: type("B", (), {"verdict": "bistable"}))
    r = CliRunner().invoke(cli, ["switch-force", "-d", "60", "-p", "0.8", "--knit-stiffness", "200",
                                 "--csv", str(tmp_path / "c.csv"), "--plot", str(tmp_path / "c.png")])
    assert r.exit_code == 0, r.output
    assert (tmp_path / "c.png").read_bytes() == path_plot.curve_png(curve, "bistable")
    assert (tmp_path / "c.csv").read_text() == curve_csv(curve, 200.0)
