"""The machine and hoop catalogue: the shipped data, the user's own file, its validation, and
the one machine and hoop API (``Catalogue.machine``, ``Machine.hoop`` / ``largest_hoop`` /
``choose_hoop``, ``DEFAULT_MACHINE``)."""
import copy
import json

import pytest

from stitchswitch.errors import InvalidInputError
from stitchswitch.layout.embroidery import export, machines
from stitchswitch.layout.embroidery.hoop_spec import Hoop


def builtin_obj():
    from importlib import resources
    return json.loads(resources.files("stitchswitch").joinpath("data/machines.json").read_text())


def test_builtin_550e_hoops():
    m = machines.builtin_catalogue().machine("janome-550e")
    assert m.label == "Janome MemoryCraft 550E" and m.stitches_per_minute == 860
    got = {h.name: (h.width_mm, h.height_mm, h.jef_code) for h in m.hoops}
    assert got == {"SQ14b": (140, 140, 2), "RE20b": (140, 200, 2), "SQ20b": (200, 200, 4),
                   "RE36b": (200, 360, None)}
    for h in m.hoops:
        assert 0 < h.margin_mm < min(h.width_mm, h.height_mm) / 2 and h.frame_width_mm > 0
    assert m.default_format in export.supported_formats()
    # the catalogue file passes the same validation as a user's file, formats included
    again = machines.machines_from_dict(builtin_obj(), "x", export.supported_formats())[0]
    assert again.hoops == m.hoops and again.default_format == m.default_format


def test_default_machine_and_its_speed():
    m = machines.default_machine()
    assert machines.DEFAULT_MACHINE == "janome-550e" and m.name == machines.DEFAULT_MACHINE
    assert m is machines.builtin_catalogue().machine() is machines.catalogue().machine("JANOME-550E")
    from stitchswitch.layout.embroidery.stitches import StitchParams
    from stitchswitch.layout.garment.design import MachineSpec
    assert MachineSpec().name == machines.DEFAULT_MACHINE
    assert StitchParams().stitches_per_minute == m.stitches_per_minute       # read from the catalogue
    assert StitchParams(stitches_per_minute=600).stitches_per_minute == 600


def test_hoop_lookup_largest_and_choice():
    m = machines.default_machine()
    old_style = Hoop("X", 100.0, 120.0, None)                 # the 4-field constructor still works
    assert old_style.margin_mm == 0.0 and old_style.fits(100, 120) and not old_style.fits(101, 1)
    assert m.hoop("sq20B") is m.hoops[2] and m.hoop("SQ20b").name == "SQ20b"
    assert m.largest_hoop().name == "RE36b"
    assert m.choose_hoop(100, 150).name == "RE20b"
    assert m.choose_hoop(150, 150).name == "SQ20b"
    assert m.choose_hoop(100, 100, "re36b").name == "RE36b"
    assert [h.name for h in m.hoops_fitting(150, 300)] == ["RE36b"]
    with pytest.raises(InvalidInputError, match="fits no hoop; the largest is RE36b 200 x 360 mm"):
        m.choose_hoop(250, 250)
    with pytest.raises(InvalidInputError, match="150.0 x 150.0 mm design does not fit the hoop SQ14b"):
        m.choose_hoop(150, 150, "SQ14b")
    with pytest.raises(InvalidInputError, match=r"'XL' is not a hoop of the janome-550e \(hoops: "
                                                r"SQ14b, RE20b, SQ20b, RE36b\)"):
        m.choose_hoop(10, 10, "XL")
    square = machines.Machine("m", "M", 100.0, "dst", (Hoop("A", 100, 200, None), Hoop("B", 200, 100, None)))
    assert square.largest_hoop().name == "A"                  # equal areas: the first


def test_hoop_geometry():
    h = Hoop("R", 140.0, 200.0, 2, margin_mm=5.0, frame_width_mm=20.0)
    assert h.field_mm(0) == (140, 200) and h.field_mm(90) == (200, 140)
    assert h.usable_mm(90) == (190, 130) and h.outer_mm(0) == (180, 240)
    assert h.orientations == (0, 90) and Hoop("S", 50, 50, None).orientations == (0,)


def test_user_machine_added_and_replacing(tmp_path):
    obj = builtin_obj()
    mine = copy.deepcopy(obj["machines"][0])
    mine.update(name="my-machine", label="Mine", default_format="dst")
    mine["hoops"] = [{"name": "H1", "width_mm": 100, "height_mm": 100, "margin_mm": 3,
                      "frame_width_mm": 15, "jef_code": None}]
    measured = copy.deepcopy(obj["machines"][0])
    measured["hoops"][0]["frame_width_mm"] = 18.5
    f = tmp_path / "m.json"
    f.write_text(json.dumps({"format": "stitchswitch machines", "version": 1,
                             "machines": [mine, measured]}))
    cat = machines.catalogue(f)
    assert cat.names() == ("my-machine", "janome-550e")
    assert cat.machine("MY-MACHINE").hoop("h1") == Hoop("H1", 100, 100, None, 3, 15)
    assert cat.machine("janome-550e").hoop("SQ14b").frame_width_mm == 18.5
    assert cat.machine("janome-550e").source.startswith("machines file ")
    assert machines.catalogue().machine("janome-550e").hoop("SQ14b").frame_width_mm == 25


def _variant(path, edit):
    obj = builtin_obj()
    edit(obj)
    path.write_text(json.dumps(obj))
    return path


@pytest.mark.parametrize("edit,message", [
    (lambda o: o["machines"][0]["hoops"][1].update(margin_mm=-3),
     "$.machines[0].hoops[1].margin_mm: -3 must be >= 0 mm"),
    (lambda o: o["machines"][0]["hoops"][0].update(width_mm="wide"),
     "$.machines[0].hoops[0].width_mm: 'wide' is not a number > 0 mm"),
    (lambda o: o["machines"][0]["hoops"][0].update(height_mm=None),
     "$.machines[0].hoops[0].height_mm: null is not a number > 0 mm"),
    (lambda o: o["machines"][0]["hoops"][2].update(margin_mm=100),
     "$.machines[0].hoops[2].margin_mm: 100 leaves no usable area in a 200 x 200 mm field"),
    (lambda o: o["machines"][0]["hoops"][0].update(jef_code=True),
     "$.machines[0].hoops[0].jef_code: true is not an integer >= 0 or null"),
    (lambda o: o["machines"][0]["hoops"][0].update(jef_code=-1),
     "$.machines[0].hoops[0].jef_code: -1 must be >= 0"),
    (lambda o: o["machines"][0]["hoops"][0].update(colour="red"),
     "$.machines[0].hoops[0].colour: unknown key (allowed: name, width_mm, height_mm, margin_mm, "
     "frame_width_mm, jef_code, notes)"),
    (lambda o: o["machines"][0]["hoops"][3].pop("frame_width_mm"),
     "$.machines[0].hoops[3].frame_width_mm: missing"),
    (lambda o: o["machines"][0]["hoops"][3].update(name="sq14B"),
     "$.machines[0].hoops[3].name: 'sq14B' is already the name of $.machines[0].hoops[0] ('SQ14b'; "
     "case is ignored)"),
    (lambda o: o["machines"][0]["hoops"][1].update(notes=3),
     "$.machines[0].hoops[1].notes: must be a string, got a number (3)"),
    (lambda o: o["machines"][0].update(default_format="xyz"),
     "$.machines[0].default_format: 'xyz' is not an export format (dst, exp, jef, pes, vp3)"),
    (lambda o: o["machines"][0].update(stitches_per_minute=0),
     "$.machines[0].stitches_per_minute: 0 must be > 0"),
    (lambda o: o["machines"][0].update(hoops=[]),
     "$.machines[0].hoops: must be a non-empty array, got an empty one"),
    (lambda o: o["machines"].append(dict(o["machines"][0], name="JANOME-550E")),
     "$.machines[1].name: 'JANOME-550E' is already the name of $.machines[0]"),
    (lambda o: o.update(version=2), "$.version: 2 is not a supported version (1)"),
    (lambda o: o.update(format="other"), "$.format: 'other' must be 'stitchswitch machines'"),
    (lambda o: o.update(machines={}), "$.machines: must be a non-empty array, got an object"),
])
def test_validation_names_the_field(tmp_path, edit, message):
    f = _variant(tmp_path / "bad.json", edit)
    with pytest.raises(InvalidInputError) as err:
        machines.load_machines(f, export.supported_formats())
    assert str(err.value).startswith(f"machines file {str(f)!r}: {message}")


def test_export_formats_are_checked_only_when_given(tmp_path):
    f = _variant(tmp_path / "fmt.json", lambda o: o["machines"][0].update(default_format="XYZ"))
    assert machines.load_machines(f)[0].default_format == "xyz"          # no list: not checked here
    with pytest.raises(InvalidInputError, match=r"\$.machines\[0\].default_format: 'xyz' is not"):
        machines.catalogue(f, export.supported_formats())


def test_machines_module_does_not_import_the_export_registry():
    import ast
    import inspect
    tree = ast.parse(inspect.getsource(machines))
    imported = {n.module for n in ast.walk(tree) if isinstance(n, ast.ImportFrom)}
    assert not any(m and m.endswith(".export") for m in imported)


def test_unreadable_or_invalid_json(tmp_path):
    with pytest.raises(InvalidInputError, match="cannot be read"):
        machines.load_machines(tmp_path / "missing.json")
    f = tmp_path / "broken.json"
    f.write_text("{\"format\": ")
    with pytest.raises(InvalidInputError, match="not valid JSON"):
        machines.load_machines(f)
    f.write_text('{"format": "stitchswitch machines", "format": "x", "version": 1, "machines": []}')
    with pytest.raises(InvalidInputError, match=r": \$.format: duplicate key"):
        machines.load_machines(f)


def test_unknown_machine_and_hoop():
    cat = machines.catalogue()
    with pytest.raises(InvalidInputError, match=r"unknown machine 'brother' \(machines: "
                                                r"janome-550e\)"):
        cat.machine("brother")
    with pytest.raises(InvalidInputError, match=r"'XL' is not a hoop of the janome-550e \(hoops: "
                                                r"SQ14b, RE20b, SQ20b, RE36b\)"):
        cat.machine("janome-550e").hoop("XL")
