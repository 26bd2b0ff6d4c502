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
