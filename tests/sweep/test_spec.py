"""``--vary NAME=SPEC``: ranges, lists and single values read as the flags read them."""

from __future__ import annotations

import math

import pytest
from hypothesis import given
from hypothesis import strategies as st

from onefold_cad.flags.parser import UsageError, parse_design_flags
from onefold_cad.sweep.spec import MAX_COUNT, flag_named, parse_vary, unit_kind

#: Ends inside the flag's allowed range (alpha, beta: deg in (0, 90)).
ANGLE = st.floats(0.001, 89.999, allow_nan=False)


def test_a_range_with_a_count_is_that_many_evenly_spaced_values():
    s = parse_vary("alpha=10:80:15")
    assert s.dest == "alpha" and s.is_range and s.count == 15
    assert len(s.values) == 15 and s.values[0] == 10.0 and s.values[-1] == 80.0
    steps = {round(b - a, 9) for a, b in zip(s.values, s.values[1:], strict=False)}
    assert steps == {5.0}


def test_lists_and_single_values_read_as_the_flag_reads_them():
    assert parse_vary("hc=-50,0,50").values == (-50.0, 0.0, 50.0)
    assert parse_vary("rectangle=3048x7315.2, 2438x6096").values == ("3048x7315.2", "2438x6096")
    assert parse_vary("model=exact,PAPER").values == ("exact", "paper")
    assert parse_vary("sheet-surface=mid").values == ("MID",)
    assert parse_vary("alpha=40").values == (40.0,)
    # the value --alpha gives, from the same parser
    assert parse_vary("alpha=1e1").values[0] == parse_design_flags(["--alpha", "1e1"])["alpha"]


def test_names_are_the_flags_without_dashes_in_any_spelling():
    for name in ("apex-fraction", "apex_fraction", "--apex-fraction", "APEX-FRACTION"):
        assert flag_named(name).dest == "apex_fraction"
    assert unit_kind(flag_named("alpha")) == "deg"
    assert unit_kind(flag_named("hc")) == "length"
    assert unit_kind(flag_named("density")) == "kg/m^3"
    assert unit_kind(flag_named("k-factor")) == ""


def test_a_whole_number_range_is_rounded_without_repeats():
    assert parse_vary("divisions=10:100:10").values == tuple(range(10, 101, 10))
    assert parse_vary("divisions=1:3:5").values == (1, 2, 3)


def test_a_polygon_list_is_separated_by_bars():
    s = parse_vary("polygon=1,0;0,1;-1,0;0,-1|2,0;0,2;-2,0;0,-2")
    assert len(s.values) == 2 and s.values[0] == "1,0;0,1;-1,0;0,-1"


@given(ANGLE, ANGLE, st.integers(2, 60))
def test_every_range_in_the_allowed_range_gives_its_count_between_its_ends(a, b, n):
    lo, hi = sorted((a, b))
    if not lo < hi:
        return
    s = parse_vary(f"beta={lo!r}:{hi!r}:{n}")
    assert len(s.values) == n and s.values[0] == lo and s.values[-1] == hi
    assert all(lo <= v <= hi for v in s.values)
    assert all(x < y for x, y in zip(s.values, s.values[1:], strict=False))


@given(st.lists(st.floats(-1e6, 1e6, allow_nan=False), min_size=1, max_size=8))
def test_a_list_of_numbers_reads_back_exactly_each_once(values):
    s = parse_vary("hc=" + ",".join(repr(v) for v in values))
    assert s.values == tuple(dict.fromkeys(float(v) for v in values))


@given(ANGLE, ANGLE)
def test_a_range_without_a_count_keeps_its_ends_for_the_samplers(a, b):
    lo, hi = sorted((a, b))
    if not lo < hi:
        return
    s = parse_vary(f"alpha={lo!r}:{hi!r}")
    assert (s.low, s.high, s.count, s.values) == (lo, hi, None, ())
    three = s.with_count(3).values
    assert three[0] == lo and three[2] == hi and math.isclose(three[1], (lo + hi) / 2)


@pytest.mark.parametrize(
    ("text", "says"),
    [
        ("alpha", "must be NAME=SPEC"),
        ("=10:20:3", "must be NAME=SPEC"),
        ("colour=1,2", "not a design flag (one of: model, units, alpha"),
        ("alpha=", "no values"),
        ("alpha=80:10:5", "empty range"),
        ("alpha=10:10:5", "empty range"),
        ("alpha=10:80:1", "count N must be in [2, "),
        (f"alpha=10:80:{MAX_COUNT + 1}", "count N must be in"),
        ("alpha=10:80:x", "count N 'x' is not a whole number"),
        ("alpha=10:80:5:2", "LO:HI or LO:HI:N"),
        ("alpha=ten:80:5", "alpha 'ten' is not a number"),
        ("alpha=10,,20", "an empty value"),
        ("alpha=nan", "finite"),
        ("alpha=-inf:10", "finite"),
        ("model=exact,wood", "model must be one of exact, paper"),
        ("rectangle=1x2:3x4", "takes no range"),
        ("divisions=2.5", "not a whole number"),
    ],
)
def test_a_bad_spec_is_one_line_naming_it(text, says):
    with pytest.raises(UsageError) as err:
        parse_vary(text)
    msg = str(err.value)
    assert msg.startswith(f"--vary {text}") and says in msg and "\n" not in msg
