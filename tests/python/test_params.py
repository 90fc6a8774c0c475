"""movseg.Params: every field of include/movseg/params.h, with its name and its comment."""
import re

import pytest

import movseg

PYTHON_KEYWORDS = {"lambda"}


def header_fields(source_dir):
    """Field names declared in struct Params, read independently of the bindings' generator."""
    text = (source_dir / "include/movseg/params.h").read_text()
    body = text.split("struct Params {", 1)[1].split("\n};", 1)[0]
    names = re.findall(r"^\s*[\w:]+\s+(\w+)\s*(?:=[^;]*)?;", body, re.MULTILINE)
    return [name + "_" if name in PYTHON_KEYWORDS else name for name in names]


def attributes():
    return {name: value for name, value in vars(movseg.Params).items() if isinstance(value, property)}


def test_every_header_field_is_an_attribute_with_its_comment(source_dir):
    fields = header_fields(source_dir)
    assert len(fields) > 20
    assert set(fields) == set(attributes())
    header = (source_dir / "include/movseg/params.h").read_text()
    for name, attribute in attributes().items():
        doc = attribute.__doc__
        assert doc, name
        assert doc.splitlines()[0] in header, name


def test_keywords_set_fields_and_values_round_trip():
    defaults = movseg.Params()
    changed = {}
    for name in attributes():
        value = getattr(defaults, name)
        if isinstance(value, bool):
            changed[name] = not value
        elif isinstance(value, int):
            changed[name] = value + 1
        elif isinstance(value, float):
            changed[name] = value + 0.5
        else:
            changed[name] = movseg.MotionModel.homography
    params = movseg.Params(**changed)
    for name, value in changed.items():
        assert getattr(params, name) == value, name
        setattr(defaults, name, value)
        assert getattr(defaults, name) == value, name
    assert repr(params) == repr(defaults)
    assert movseg.Segmenter(movseg.Params(lambda_=123.0)).params.lambda_ == 123.0


def test_bad_values_raise_value_error():
    with pytest.raises(ValueError, match="gmm_clusters"):
        movseg.Segmenter(movseg.Params(gmm_clusters=0))
    with pytest.raises(ValueError):
        movseg.Params(lambda_=-1).check()
    with pytest.raises(ValueError):
        movseg.createMovingCameraSubtractor(movseg.Params(gmm_clusters=0))


def test_unknown_names_and_wrong_types_raise_type_error():
    with pytest.raises(TypeError, match="no field 'lambda'"):
        movseg.Params(**{"lambda": 1.0})
    with pytest.raises(TypeError, match="lambda_"):
        movseg.Params(lambda_="high")
