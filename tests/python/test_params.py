"""movseg.Params: every field of include/movseg/params.def, with its name and its doc."""
import copy
import re

import pytest

import movseg

PYTHON_KEYWORDS = {"lambda"}
ENTRY = re.compile(r'^MOVSEG_PARAM\(([\w:]+),\s*(\w+),[^"]*"[^"]*",\s*"([^"]*)"\)', re.M)


def table_fields(source_dir):
    """(python name, doc) of every entry of params.def, read independently of the bindings."""
    text = (source_dir / "include/movseg/params.def").read_text()
    return {(name + "_" if name in PYTHON_KEYWORDS else name): doc
            for _, name, doc in ENTRY.findall(text)}


def attributes():
    return {name: value for name, value in vars(movseg.Params).items() if isinstance(value, property)}


def test_every_table_field_is_an_attribute_documented_by_its_entry(source_dir):
    fields = table_fields(source_dir)
    assert len(fields) > 25
    assert set(fields) == set(attributes())
    for name, attribute in attributes().items():
        assert attribute.__doc__.startswith(fields[name]), name
    assert all(f"\n    {name}=" in repr(movseg.Params()) for name in fields)


def valid_change(name, value):
    """Another value of the field that check() accepts: each field has its own range."""
    if isinstance(value, bool):
        return not value
    if isinstance(value, int):
        candidates = [value + 2, value - 2]  # odd window sides stay odd
    elif isinstance(value, float):
        candidates = [value + 0.5, value * 0.9, value + 0.01]
    else:
        return {"method": "diff", "motion_model": "homography"}[name]
    for candidate in candidates:
        try:
            movseg.Params(**{name: candidate}).check()
            return candidate
        except ValueError:
            pass
    raise AssertionError(f"no other valid value found for {name}")


def test_keywords_set_fields_and_values_round_trip():
    defaults = movseg.Params()
    changed = {name: valid_change(name, getattr(defaults, name)) for name in attributes()}
    params = movseg.Params(**changed)
    for name, value in changed.items():
        assert getattr(params, name) == value, name
        setattr(defaults, name, value)
        assert getattr(defaults, name) == value, name
    assert repr(params) == repr(defaults) and params == defaults
    assert params != movseg.Params() and params is not None
    copied = copy.deepcopy(params)
    assert copied == params and copied is not params and copy.copy(params) == params
    params.check()
    assert movseg.Segmenter(movseg.Params(lambda_=123.0)).params.lambda_ == 123.0


def test_bad_values_raise_value_error():
    with pytest.raises(ValueError, match="gmm_clusters"):
        movseg.Segmenter(movseg.Params(gmm_clusters=0))
    with pytest.raises(ValueError):
        movseg.Params(lambda_=-1).check()
    with pytest.raises(ValueError):
        movseg.createMovingCameraSubtractor(movseg.Params(gmm_clusters=0))


def test_choices_are_names():
    assert movseg.Params().method == "dense"
    with pytest.raises(ValueError, match="one of paper, diff"):
        movseg.Params(method="fast")


def test_unknown_names_and_wrong_types_raise_type_error():
    with pytest.raises(TypeError, match="no field 'lambda'"):
        movseg.Params(**{"lambda": 1.0})
    with pytest.raises(TypeError, match="lambda_"):
        movseg.Params(lambda_="high")
