"""Parameter objects: validation with one clear message naming the field and the bad value,
accepted boundary values, frozen instances, Material.replace and as_dict."""
import dataclasses
import math

import pytest

from stitchswitch.errors import InvalidInputError
from stitchswitch.reduced.model.params import DEFAULT_MATERIAL, DIAMETER_RANGE_MM, Material, Patch

STIFFNESSES = ("w_b_emb", "w_b_fab", "k_r_emb", "k_r_fab", "k_theta_emb", "k_theta_fab")
FLOAT_FIELDS = STIFFNESSES + ("w_log", "c_emb", "c_fab", "jam", "c_jam", "gamma_mm", "eta", "dr_max_mm",
                              "compression_floor", "domain_max_rb")


def value_spellings(value):
    """The ways a message may reasonably print a bad value."""
    out = {repr(value), str(value)}
    if isinstance(value, float) and math.isfinite(value):
        out.add(format(value, "g"))
    return out


def assert_names(excinfo, field, value):
    msg = str(excinfo.value)
    assert field in msg, msg
    assert any(s in msg for s in value_spellings(value)), (value, msg)


# -------------------------------------------------------------------------------- Patch

@pytest.mark.parametrize("d", [0, 0.0, -1.0, -20.0])
def test_patch_non_positive_diameter(d):
    with pytest.raises(InvalidInputError) as info:
        Patch(d, 0.5)
    assert_names(info, "diameter_mm", d)


@pytest.mark.parametrize("d", [1.0, 9.99, 9.999999, 150.000001, 150.5, 200.0, 1e6])
def test_patch_diameter_outside_supported_range(d):
    with pytest.raises(InvalidInputError) as info:
        Patch(d, 0.5)
    assert_names(info, "diameter_mm", d)


@pytest.mark.parametrize("d", [float("nan"), float("inf"), float("-inf")])
def test_patch_non_finite_diameter(d):
    with pytest.raises(InvalidInputError) as info:
        Patch(d, 0.5)
    assert_names(info, "diameter_mm", d)


@pytest.mark.parametrize("d", ["abc", "", "20mm", "nan", "inf", None, [20.0], {}])
def test_patch_non_numeric_diameter(d):
    with pytest.raises(InvalidInputError) as info:
        Patch(d, 0.5)
    assert_names(info, "diameter_mm", d)


@pytest.mark.parametrize("fill", [0, 0.0, -0.0, -0.5, 1.0000001, 1.5, 100.0])
def test_patch_fill_outside_unit_interval(fill):
    with pytest.raises(InvalidInputError) as info:
        Patch(20.0, fill)
    assert_names(info, "fill", fill)


@pytest.mark.parametrize("fill", [float("nan"), float("inf"), float("-inf"), "half", None])
def test_patch_fill_not_a_finite_number(fill):
    with pytest.raises(InvalidInputError) as info:
        Patch(20.0, fill)
    assert_names(info, "fill", fill)


def test_patch_diameter_checked_before_fill_and_messages_name_the_right_field():
    with pytest.raises(InvalidInputError) as info:
        Patch(20.0, 0.0)
    assert "fill" in str(info.value) and "diameter_mm" not in str(info.value)
    with pytest.raises(InvalidInputError) as info:
        Patch(5.0, 0.5)
    assert "diameter_mm" in str(info.value) and "fill" not in str(info.value)


def test_invalid_input_error_is_a_value_error():
    with pytest.raises(ValueError):
        Patch(-1.0, 0.5)


@pytest.mark.parametrize("d", [10, 10.0, 150, 150.0, 17.0, 99.5])
@pytest.mark.parametrize("fill", [1.0, 1, 1e-9, 0.5])
def test_patch_accepts_boundaries(d, fill):
    patch = Patch(d, fill)
    assert patch.diameter_mm == d and patch.fill == fill
    assert type(patch.diameter_mm) is float and type(patch.fill) is float


def test_supported_range_is_the_documented_one():
    assert DIAMETER_RANGE_MM == (10.0, 150.0)


def test_patch_is_frozen_and_hashable():
    patch = Patch(20.0, 0.5)
    with pytest.raises(dataclasses.FrozenInstanceError):
        patch.diameter_mm = 30.0
    with pytest.raises(dataclasses.FrozenInstanceError):
        patch.fill = 0.1
    assert patch == Patch(20, 0.5)
    assert hash(patch) == hash(Patch(20.0, 0.5))
    assert patch.diameter_mm == 20.0 and patch.fill == 0.5


# ----------------------------------------------------------------------------- Material

def material(**changes):
    values = DEFAULT_MATERIAL.as_dict()
    values.update(changes)
    return Material(**values)


@pytest.mark.parametrize("value", [0, 0.0, -1e-12, -1.0])
@pytest.mark.parametrize("field", STIFFNESSES)
def test_material_non_positive_stiffness(field, value):
    with pytest.raises(InvalidInputError) as info:
        material(**{field: value})
    assert_names(info, field, value)


@pytest.mark.parametrize("value", [float("nan"), float("inf"), float("-inf"), "x", None])
@pytest.mark.parametrize("field", FLOAT_FIELDS)
def test_material_non_finite_or_non_numeric(field, value):
    with pytest.raises(InvalidInputError) as info:
        material(**{field: value})
    assert_names(info, field, value)


@pytest.mark.parametrize("value", [-1e-9, -0.05, -1.0])
def test_material_negative_w_log(value):
    with pytest.raises(InvalidInputError) as info:
        material(w_log=value)
    assert_names(info, "w_log", value)


def test_material_zero_w_log_accepted():
    assert material(w_log=0.0).w_log == 0.0


@pytest.mark.parametrize("value", [0, 0.0, -1.0])
def test_material_non_positive_gamma(value):
    with pytest.raises(InvalidInputError) as info:
        material(gamma_mm=value)
    assert_names(info, "gamma_mm", value)


@pytest.mark.parametrize("value", [0.0, -1.7, 0.5, 1.0, 3.0000001, 3.5, 10.0])
def test_material_eta_outside_range(value):
    with pytest.raises(InvalidInputError) as info:
        material(eta=value)
    assert_names(info, "eta", value)


@pytest.mark.parametrize("value", [1.0000001, 1.7, 3.0, 3])
def test_material_eta_accepted(value):
    assert material(eta=value).eta == value


@pytest.mark.parametrize("value", [0, 0.0, -0.5])
def test_material_non_positive_dr_max(value):
    with pytest.raises(InvalidInputError) as info:
        material(dr_max_mm=value)
    assert_names(info, "dr_max_mm", value)


@pytest.mark.parametrize("field, value", [
    ("compression_floor", 0), ("compression_floor", 0.0), ("compression_floor", -0.01),
    ("compression_floor", 1.0), ("c_emb", -0.01), ("c_emb", 1.0), ("c_fab", -1e-9), ("c_fab", 1.5),
    ("jam", -0.1), ("jam", 1.0)])
def test_material_compressive_response_outside_its_interval(field, value):
    with pytest.raises(InvalidInputError) as info:
        material(**{field: value})
    assert_names(info, field, value)


@pytest.mark.parametrize("field, value", [
    ("compression_floor", 1e-12), ("compression_floor", 0.999), ("c_emb", 0.0), ("c_emb", 0.5),
    ("c_fab", 0.0), ("c_fab", 0.2), ("jam", 0.0), ("jam", 0.95)])
def test_material_compressive_response_accepted(field, value):
    changes = {field: value} | ({"c_fab": 0.01} if (field, value) == ("jam", 0.0) else {})
    assert getattr(material(**changes), field) == value


def test_material_without_jamming_or_knit_stiffness_has_no_minimizer():
    with pytest.raises(InvalidInputError, match="^jam: 0.0 with c_jam"):
        material(jam=0.0, c_fab=0.0)


@pytest.mark.parametrize("value", [3, None, "tab\there", "x" * 301])
def test_material_label_must_be_short_printable_text(value):
    with pytest.raises(InvalidInputError, match="^label: "):
        material(label=value)


def test_material_huge_integer_is_not_a_number_error():
    with pytest.raises(InvalidInputError, match="^w_log: "):
        material(w_log=10 ** 400)


@pytest.mark.parametrize("value", [300.5, 20.1, "300", None, float("nan"), float("inf"), [300]])
def test_material_n_nodes_not_an_integer(value):
    with pytest.raises(InvalidInputError) as info:
        material(n_nodes=value)
    assert_names(info, "n_nodes", value)


@pytest.mark.parametrize("value", [True, False])
def test_material_n_nodes_bool_rejected(value):
    with pytest.raises(InvalidInputError) as info:
        material(n_nodes=value)
    assert_names(info, "n_nodes", value)


@pytest.mark.parametrize("value", [-300, 0, 1, 19, 20001, 10 ** 6, 19.0, 20001.0])
def test_material_n_nodes_out_of_range(value):
    with pytest.raises(InvalidInputError) as info:
        material(n_nodes=value)
    assert_names(info, "n_nodes", value)


@pytest.mark.parametrize("value", [20, 300, 20000, 20.0, 300.0])
def test_material_n_nodes_accepted(value):
    m = material(n_nodes=value)
    assert m.n_nodes == value and type(m.n_nodes) is int


def test_material_float_fields_are_floats():
    m = material(w_b_emb=3, eta=2, gamma_mm=5, dr_max_mm=1)
    for name in FLOAT_FIELDS:
        assert type(getattr(m, name)) is float, name


def test_material_missing_required_coefficient():
    values = DEFAULT_MATERIAL.as_dict()
    del values["k_r_emb"]
    with pytest.raises(TypeError):
        Material(**values)


# ---------------------------------------------------------------------- Material.replace

def test_replace_changes_only_the_given_fields():
    m = DEFAULT_MATERIAL.replace(eta=1.5, n_nodes=400)
    assert m.eta == 1.5 and m.n_nodes == 400
    for name, value in DEFAULT_MATERIAL.as_dict().items():
        if name not in ("eta", "n_nodes"):
            assert getattr(m, name) == value, name
    # The original is untouched.
    assert DEFAULT_MATERIAL.eta == 1.7 and DEFAULT_MATERIAL.n_nodes == 300


def test_replace_without_changes_is_equal():
    assert DEFAULT_MATERIAL.replace() == DEFAULT_MATERIAL


@pytest.mark.parametrize("field, value", [
    ("eta", 0.5), ("eta", 3.5), ("k_r_emb", 0.0), ("w_b_fab", -1.0), ("w_log", -0.1),
    ("gamma_mm", 0.0), ("jam", 1.0), ("n_nodes", 19), ("n_nodes", True),
    ("n_nodes", 300.5), ("dr_max_mm", 0.0), ("k_theta_fab", float("nan")),
])
def test_replace_validates(field, value):
    with pytest.raises(InvalidInputError) as info:
        DEFAULT_MATERIAL.replace(**{field: value})
    assert_names(info, field, value)


def test_replace_rejects_unknown_fields():
    with pytest.raises(InvalidInputError) as info:
        DEFAULT_MATERIAL.replace(stiffness=1.0)
    assert "stiffness" in str(info.value)
    with pytest.raises(InvalidInputError) as info:
        DEFAULT_MATERIAL.replace(eta=1.5, foo=1, bar=2)
    assert "foo" in str(info.value) and "bar" in str(info.value)


# ------------------------------------------------------------------- frozen, as_dict

def test_material_is_frozen():
    with pytest.raises(dataclasses.FrozenInstanceError):
        DEFAULT_MATERIAL.eta = 2.0
    with pytest.raises(dataclasses.FrozenInstanceError):
        DEFAULT_MATERIAL.n_nodes = 10
    with pytest.raises(dataclasses.FrozenInstanceError):
        DEFAULT_MATERIAL.k_r_emb = -1.0
    assert DEFAULT_MATERIAL.eta == 1.7


def test_default_material_round_trips_through_as_dict():
    d = DEFAULT_MATERIAL.as_dict()
    assert list(d) == [f.name for f in dataclasses.fields(Material)]
    again = Material(**d)
    assert again == DEFAULT_MATERIAL
    assert again.as_dict() == d
    assert hash(again) == hash(DEFAULT_MATERIAL)


def test_as_dict_is_a_copy():
    d = DEFAULT_MATERIAL.as_dict()
    d["eta"] = 2.9
    assert DEFAULT_MATERIAL.eta == 1.7


def test_default_material_uses_the_papers_discretization():
    # Section 4: eta = 1.7, N = 300 nodes, dR_max = 0.5 mm.
    assert DEFAULT_MATERIAL.eta == 1.7
    assert DEFAULT_MATERIAL.n_nodes == 300
    assert DEFAULT_MATERIAL.dr_max_mm == 0.5
