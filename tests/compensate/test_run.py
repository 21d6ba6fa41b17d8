"""The compensation's verdict, from standing forms given by hand."""

from __future__ import annotations

from onefold_cad.compensate.optimise import Search
from onefold_cad.compensate.run import FormReport, _verdict
from onefold_cad.compensate.target import Target
from onefold_cad.templates import load_template


def _form(stands: bool, height: float | None, span: float | None) -> FormReport:
    return FormReport(stands, None, None, height, span, None, 10.0 if stands else None, None)


def test_a_compensated_fold_that_falls_says_what_the_start_reaches():
    target = Target("size", load_template("patkau-one-fold"), 2800.0, 5800.0)
    ok, text = _verdict(target, {}, _form(True, 2799.2, 6051.9), _form(False, None, None),
                        Search())  # fmt: skip
    assert not ok
    assert text == ("the compensated fold does not stand (uncompensated, the start stands "
                    "2799.2 mm high and 6051.9 mm wide)")  # fmt: skip
    ok, text = _verdict(target, {}, _form(False, None, None), _form(False, None, None), Search())
    assert not ok and text == "the compensated fold does not stand"


def test_a_size_within_one_percent_is_met():
    target = Target("size", load_template("patkau-one-fold"), 2800.0, 5800.0)
    ok, text = _verdict(target, {}, _form(True, 2700, 6000), _form(True, 2820.0, 5760.0), Search())
    assert ok and text.startswith("met: height 2820 mm (0.71 % off), span 5760 mm (0.69 % off)")
