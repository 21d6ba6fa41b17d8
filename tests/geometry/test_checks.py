"""Small numeric helpers of geometry/validate.py."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from onefold_cad.errors import InvalidParameterError
from onefold_cad.geometry.numeric import sorted_unique

_VALUES = st.sampled_from([0.0, -0.0, 1.0, 2.5, -1.0, 1e-300, float("inf"), -float("inf")])


@settings(max_examples=200, deadline=None)
@given(
    values=st.lists(st.one_of(_VALUES, st.just(float("nan")), st.floats(-3, 3)), max_size=40),
    ints=st.booleans(),
    column=st.booleans(),
)
def test_sorted_unique_is_numpys_unique(values: list[float], ints: bool, column: bool) -> None:
    # the same values, dtype, shape and signs of zero as np.unique (NaNs as one)
    a = np.array(values, dtype=float)
    if ints:
        a = np.nan_to_num(a, posinf=9, neginf=-9).astype(np.int64)
    if column:
        a = a.reshape(-1, 1)
    want, got = np.unique(a), sorted_unique(a)
    assert got.dtype == want.dtype and got.shape == want.shape
    assert np.array_equal(got, want, equal_nan=True)
    assert np.array_equal(np.signbit(got), np.signbit(want))
    assert got is not a and (not len(a) or not np.shares_memory(got, a))


def test_a_refusal_shows_the_value_as_given():
    """apex_fraction 0.999999999999 was refused with 'got 1' (``:g`` keeps 6
    digits): the value is shown with every digit it needs to read back."""
    from onefold_cad import Sheet
    from onefold_cad.geometry.checks import shown

    with pytest.raises(InvalidParameterError, match=r"got 0\.999999999999$"):
        Sheet.rectangle(100.0, 50.0, apex_fraction=0.999999999999)
    assert [shown(x) for x in (0.5, 1e308, -1.0, 1e-320, 100.0)] == [
        "0.5", "1e+308", "-1", "1e-320", "100",
    ]  # fmt: skip
    assert shown(0.1 + 0.2) == "0.30000000000000004"
    assert shown(float("nan")) == "nan" and shown(float("-inf")) == "-inf"
