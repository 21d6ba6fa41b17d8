"""The .3dm's user strings: strings as themselves, other values as JSON that
reads back exactly; the report's key numbers under ``report.``, null where
the report has none; the design's parameters under their template keys."""

from __future__ import annotations

import json

import pytest

from onefold_cad import Design, FrameCurve, Material, Sheet, fold_design
from onefold_cad.export.rhino_strings import (
    KEY_NUMBERS,
    design_strings,
    report_strings,
    user_string,
)


@pytest.mark.parametrize("value", [0.1 + 0.2, 1e-300, -7, True, None, [1.5, 2.25], "UP"])
def test_a_value_reads_back_exactly(value):
    text = user_string(value)
    assert (text if isinstance(value, str) else json.loads(text)) == value
    assert isinstance(text, str)


def test_key_numbers_are_the_reports_and_null_without_a_density():
    design = Design("k", FrameCurve(40, 35, h_c=3.0), Sheet.rectangle(100, 60, 0.3))
    folded = fold_design(design)
    strings = report_strings(design, folded)
    assert set(strings) == {f"report.{k}" for k in KEY_NUMBERS}
    assert strings["report.mass.value"] == "null" and strings["report.mass.unit"] == "null"
    for half in folded.crease:  # the fold's own numbers
        fold = json.loads(strings[f"report.fold_angles_deg.{half.name}"])
        assert fold == pytest.approx(half.fold_angle_deg, rel=1e-12)
        assert strings[f"report.bend.{half.name}"] == half.bend
        assert json.loads(strings[f"report.crease.{half.name}.length"]) == pytest.approx(
            half.length
        )
    assert json.loads(strings["report.sheet.area"]) == pytest.approx(100 * 60, rel=1e-12)
    assert isinstance(json.loads(strings["report.warnings"]), list)


def test_design_strings_are_its_template_keys():
    design = Design(
        "d",
        FrameCurve(41, 33, h_c=2.5),
        Sheet.rectangle(80, 50, 0.4),
        material=Material(thickness=1.5),
        units="in",
    )
    s = design_strings(design)
    assert float(s["frame.alpha"]) == 41.0 and float(s["frame.beta"]) == 33.0
    assert float(s["frame.h_c"]) == 2.5 and float(s["material.thickness"]) == 1.5
    assert s["units"] == "in"
