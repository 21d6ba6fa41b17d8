"""The suite's Hypothesis profile (tests/conftest.py): derandomized and without
a deadline, so no test is a timing assert on a shared machine."""

from __future__ import annotations

from hypothesis import settings


def test_the_loaded_profile_has_no_deadline_and_fixed_examples() -> None:
    assert settings.default.deadline is None
    assert settings.default.derandomize is True
    assert settings.get_profile("explore").deadline is None
