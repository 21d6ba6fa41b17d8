"""The Hops components and their helpers called directly, without a server."""

from __future__ import annotations

import pytest

from onefold_cad.errors import InvalidParameterError
from onefold_cad.hops.components import fit_answer, units_warning


@pytest.mark.parametrize(("values", "missing"), [({}, "height"), ({"height": 2800.0}, "span")])
def test_fit_without_a_target_names_it(values, missing):
    with pytest.raises(InvalidParameterError) as info:
        fit_answer(values)
    assert info.value.parameter == missing
    assert "is required" in str(info.value)


@pytest.mark.parametrize(
    ("design", "model", "names"),
    [
        ("in", "Millimeters", ("inches (units 'in')", "document's in Millimeters")),
        ("mm", "Feet", ("millimetres (units 'mm')", "document's in Feet")),
        ("ft", "Inches", ("feet (units 'ft')", "open a document in Feet")),
    ],
)
def test_a_unit_mismatch_is_a_sentence_naming_both_units(design, model, names):
    text = units_warning(design, model)
    assert text is not None
    for name in names:
        assert name in text
    assert " in in " not in f" {text} " and "is in ft" not in text  # not "the design is in in"


def test_matching_or_missing_document_units_say_nothing():
    assert units_warning("mm", "Millimeters") is None
    assert units_warning("in", None) is None
