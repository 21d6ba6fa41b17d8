"""Pareto objectives and the non-dominated designs, held to a brute force."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

from onefold_cad.flags.parser import UsageError
from onefold_cad.sweep.measures import REST, Column
from onefold_cad.sweep.pareto import Objective, costs, dominates, pareto_front, parse_objectives

COLUMNS = (*REST.columns, Column("alpha", "float", "deg", ""))


def brute_force(c: np.ndarray) -> np.ndarray:
    n = len(c)
    finite = np.all(np.isfinite(c), axis=1)
    return np.array(
        [
            finite[i] and not any(finite[j] and dominates(c[j], c[i]) for j in range(n))
            for i in range(n)
        ],
        dtype=bool,
    )


@settings(deadline=None)
@given(
    st.integers(1, 4).flatmap(
        lambda k: arrays(
            float,
            st.tuples(st.integers(0, 40), st.just(k)),
            elements=st.sampled_from([0.0, 1.0, 2.0, 3.0, 2.5, np.nan]),
        )
    )
)
def test_the_front_is_the_brute_force_s(c):
    assert np.array_equal(pareto_front(c), brute_force(c))


@settings(deadline=None, max_examples=50)
@given(
    arrays(
        float,
        st.tuples(st.integers(1, 60), st.integers(2, 3)),
        elements=st.floats(-1e3, 1e3, allow_nan=False),
    )
)
def test_continuous_costs_too(c):
    assert np.array_equal(pareto_front(c), brute_force(c))


def test_objectives_turn_values_into_costs():
    table = {"tipping_margin_deg": [5.0, 10.0], "height": [2900.0, 3050.0], "span": [1.0, 2.0]}
    objs = parse_objectives("max:tipping_margin_deg,target:height=3000,min:span", COLUMNS)
    assert [o.text for o in objs] == ["max:tipping_margin_deg", "target:height=3000", "min:span"]
    assert np.array_equal(costs(objs, table), [[-5.0, 100.0, 1.0], [-10.0, 50.0, 2.0]])
    assert Objective("target", "height", 3000.0).cost(np.array([np.nan]))[0] != 0.0


@pytest.mark.parametrize(
    ("text", "says"),
    [
        ("maximise:height", "must be max:COLUMN, min:COLUMN or target:COLUMN=VALUE"),
        ("max:", "must be max:COLUMN"),
        ("max:volume", "no number column 'volume'"),
        ("min:mass", "it needs --measure mass"),
        ("max:body", "no number column 'body'"),
        ("target:height", "target needs =VALUE"),
        ("max:height=3", "max takes no =VALUE"),
        ("target:height=tall", "'tall' is not a number"),
        ("target:height=inf", "finite"),
        ("max:height,min:height", "named twice"),
    ],
)
def test_a_bad_objective_is_one_line_naming_it(text, says):
    with pytest.raises(UsageError) as err:
        parse_objectives(text, COLUMNS, {"mass": "mass"})
    assert str(err.value).startswith("--objectives: ") and says in str(err.value)
