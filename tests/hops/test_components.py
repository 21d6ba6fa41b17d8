"""The Hops components' helpers that need no server."""

from __future__ import annotations

import pytest

from onefold_cad.hops.components import units_warning


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
