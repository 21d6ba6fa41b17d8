"""The Hops components called directly, without a server."""

from __future__ import annotations

import pytest

from onefold_cad.errors import InvalidParameterError
from onefold_cad.hops.components import fit_answer


@pytest.mark.parametrize(("values", "missing"), [({}, "height"), ({"height": 2800.0}, "span")])
def test_fit_without_a_target_names_it(values, missing):
    with pytest.raises(InvalidParameterError) as info:
        fit_answer(values)
    assert info.value.parameter == missing
    assert "is required" in str(info.value)
