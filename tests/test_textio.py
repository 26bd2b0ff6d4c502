"""Text inputs (``files.textio``): the size bound and CSV fields longer than the csv module's
own limit."""
import csv

import pytest

from stitchswitch.errors import InvalidInputError
from stitchswitch.files import textio


def test_read_text_is_bounded(tmp_path, monkeypatch):
    """A file over the limit is refused naming it, after reading no more than the limit; an
    endless source such as /dev/zero ends the same way instead of exhausting memory."""
    monkeypatch.setattr(textio, "MAX_TEXT_BYTES", 1000)
    path = tmp_path / "big.json"
    path.write_bytes(b" " * 1001)
    with pytest.raises(InvalidInputError, match=r"^material file 'big.json': larger than"):
        textio.read_text(path, "material file 'big.json'")
    path.write_bytes(b" " * 1000)
    assert textio.read_text(path, "m") == " " * 1000
    with pytest.raises(InvalidInputError, match="larger than"):
        textio.read_text("/dev/zero", "material file '/dev/zero'")


def test_csv_fields_longer_than_the_csv_limit():
    long = "x" * (csv.field_size_limit() + 10)
    source, records = textio.csv_records(f"# source: s\na,b\n1,{long}\n")
    assert source == "s" and records[1] == (3, ["1", long])
    assert csv.field_size_limit() < len(long)                      # the limit is restored
    with pytest.raises(InvalidInputError) as info:
        textio.csv_number(long, "data 'd.csv', line 3", "fill")
    assert len(str(info.value)) < 150 and "'xxx" in str(info.value)


def test_dev_zero_as_a_material_gives_one_error(tmp_path):
    """--material /dev/zero and a design whose material.file is /dev/zero: exit 2, one line."""
    import json

    from click.testing import CliRunner

    from stitchswitch.cli.main import cli

    design = tmp_path / "d.json"
    design.write_text(json.dumps({"version": 1, "pieces": [{"name": "f", "outline_mm": [
        [0, 0], [100, 0], [100, 100]]}], "patches": [], "material": {"file": "/dev/zero"}}))
    for args in (["simulate", "--material", "/dev/zero"], ["check", str(design)]):
        r = CliRunner().invoke(cli, args)
        assert r.exit_code == 2 and r.output.count("\n") == 1, r.output
        assert r.output.startswith("Error: ") and "'/dev/zero': larger than 16 MiB" in r.output


def test_a_cell_over_128_kib_through_the_loaders_and_force_data(tmp_path):
    """A huge cell is one short error naming the file, line and column (``force --data`` exits
    2); a huge note of a measured row is kept."""
    from importlib import resources

    from click.testing import CliRunner

    from stitchswitch.cli.main import cli
    from stitchswitch.validation.measured import load_measurements

    big = "9" * 200_000
    force = tmp_path / "force.csv"
    force.write_text(f"d_mm,fill,force_N,split\n40,0.8,{big}x,train\n50,0.8,0.5,val\n")
    r = CliRunner().invoke(cli, ["force", "-d", "40", "-p", "0.8", "--data", str(force)])
    assert r.exit_code == 2 and r.output.count("\n") == 1 and len(r.output) < 300
    assert f"force data {str(force)!r}, line 2, column force_N: '999" in r.output
    seed = resources.files("stitchswitch").joinpath("data/measured_synthetic.csv").read_text()
    lines = seed.splitlines()
    k = next(i for i, line in enumerate(lines) if not line.startswith("#")) + 1  # first data row
    header = lines[k - 1].split(",")
    cells = lines[k].split(",")
    measured = tmp_path / "m.csv"
    if "notes" in header:
        cells[header.index("notes")] = "n" * 200_000
        measured.write_text("\n".join(lines[:k] + [",".join(cells)] + lines[k + 1:]) + "\n")
        assert load_measurements(measured).rows[0].notes == "n" * 200_000
    cells = lines[k].split(",")
    cells[header.index("h_mm")] = big
    measured.write_text("\n".join(lines[:k] + [",".join(cells)] + lines[k + 1:]) + "\n")
    with pytest.raises(InvalidInputError) as info:
        load_measurements(measured)
    assert len(str(info.value)) < 300 and f"line {k + 1}, column h_mm" in str(info.value)


@pytest.mark.parametrize("value, message", [
    ("1" * 5000, "$.w_b_emb: 111"), ("1" + "0" * 350, "$.w_b_emb: 100"),
    ("[" * 50_000 + "]" * 50_000, "nested deeper than 32 levels")])
def test_json_numbers_and_nesting_through_a_command(tmp_path, value, message):
    """5,000-digit numbers, integers beyond the float range and deep nesting in a material
    file: exit 2 and one line naming the file and the field."""
    import json
    from importlib import resources

    from click.testing import CliRunner

    from stitchswitch.cli.main import cli

    material = json.loads(resources.files("stitchswitch").joinpath(
        "data/default_material.json").read_text())
    material["w_b_emb"] = "@@"
    path = tmp_path / "m.json"
    path.write_text(json.dumps(material).replace('"@@"', value))
    r = CliRunner().invoke(cli, ["simulate", "--material", str(path)])
    assert r.exit_code == 2 and r.output.count("\n") == 1 and len(r.output) < 300, r.output
    assert r.output.startswith(f"Error: material file {str(path)!r}: ") and message in r.output
