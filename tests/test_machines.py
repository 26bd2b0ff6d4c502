"""The machine and hoop catalogue: the shipped data, the user's own file, its validation, and
the backward-compatible ``layout.embroidery.hoops`` API."""
import copy
import json

import pytest

from stitchswitch.errors import InvalidInputError
from stitchswitch.layout.embroidery import export, hoops, machines
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


def test_hoops_module_backward_compatible():
    assert hoops.JANOME_550E_HOOPS == machines.builtin_catalogue().machine("janome-550e").hoops
    assert hoops.Hoop is Hoop
    old_style = hoops.Hoop("X", 100.0, 120.0, None)          # the 4-field constructor still works
    assert old_style.margin_mm == 0.0 and old_style.fits(100, 120) and not old_style.fits(101, 1)
    assert hoops.choose_hoop(100, 150).name == "RE20b"
    assert hoops.choose_hoop(150, 150).name == "SQ20b"
    assert [h.name for h in hoops.hoops_fitting(150, 300)] == ["RE36b"]
    with pytest.raises(InvalidInputError, match="fits no hoop; the largest is RE36b"):
        hoops.choose_hoop(250, 250)


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
     "machines[0].hoops[1].margin_mm: -3 must be >= 0"),
    (lambda o: o["machines"][0]["hoops"][0].update(width_mm="wide"),
     "machines[0].hoops[0].width_mm: 'wide' must be a finite number"),
    (lambda o: o["machines"][0]["hoops"][2].update(margin_mm=100),
     "machines[0].hoops[2].margin_mm: 100 leaves no usable area in a 200 x 200 mm field"),
    (lambda o: o["machines"][0]["hoops"][0].update(jef_code=True),
     "machines[0].hoops[0].jef_code: True must be a non-negative integer or null"),
    (lambda o: o["machines"][0]["hoops"][0].update(colour="red"),
     "machines[0].hoops[0].colour: unknown key"),
    (lambda o: o["machines"][0]["hoops"][3].pop("frame_width_mm"),
     "machines[0].hoops[3].frame_width_mm: is missing"),
    (lambda o: o["machines"][0]["hoops"][3].update(name="sq14B"),
     "machines[0].hoops[3].name: 'sq14B' appears twice"),
    (lambda o: o["machines"][0].update(default_format="xyz"),
     "machines[0].default_format: 'xyz' is not an export format"),
    (lambda o: o["machines"][0].update(stitches_per_minute=0),
     "machines[0].stitches_per_minute: 0 must be > 0"),
    (lambda o: o["machines"][0].update(hoops=[]), "machines[0].hoops: must be a non-empty array"),
    (lambda o: o.update(version=2), "version: 2 is not a supported version (1)"),
    (lambda o: o.update(format="other"), "format: 'other' must be 'stitchswitch machines'"),
])
def test_validation_names_the_field(tmp_path, edit, message):
    f = _variant(tmp_path / "bad.json", edit)
    with pytest.raises(InvalidInputError) as err:
        machines.load_machines(f)
    assert str(err.value).startswith(f"machines file {str(f)!r}: {message}")


def test_unreadable_or_invalid_json(tmp_path):
    with pytest.raises(InvalidInputError, match="cannot be read"):
        machines.load_machines(tmp_path / "missing.json")
    f = tmp_path / "broken.json"
    f.write_text("{\"format\": ")
    with pytest.raises(InvalidInputError, match="not valid JSON"):
        machines.load_machines(f)


def test_unknown_machine_and_hoop():
    cat = machines.catalogue()
    with pytest.raises(InvalidInputError, match="unknown machine 'brother'; the machines are "
                                                "janome-550e"):
        cat.machine("brother")
    with pytest.raises(InvalidInputError, match="'XL' is not a hoop of the janome-550e"):
        cat.machine("janome-550e").hoop("XL")
