"""Suite-wide test settings.

Hypothesis runs derandomized by default: every run of the suite (CI, a
clean clone, a developer's) draws the same examples, so a red run can be
repeated as it was and CI never turns red by the luck of a seed. To explore
new examples over the same ranges, run
``pytest --hypothesis-profile=explore`` (random seeds, more examples); a
failure found there is pinned with ``@example`` in the test it broke.

No example has a deadline: the machines are shared and noisy, and a
deadline is a timing assert (timings belong in ``benchmarks/``); a hang is
caught by the examples' own bounded work, not by the clock.
"""

from __future__ import annotations

from collections.abc import Callable

import pytest
from hypothesis import settings

settings.register_profile(
    "default", derandomize=True, database=None, print_blob=True, deadline=None
)
settings.register_profile(
    "explore", derandomize=False, max_examples=500, print_blob=True, deadline=None
)
settings.load_profile("default")


@pytest.fixture
def cli(capfd: pytest.CaptureFixture[str]) -> Callable[..., tuple[int, str, str]]:
    """``onefold``'s ``main()`` in this process (imports already paid): (exit
    status, stdout, stderr)."""
    from onefold_cad.cli.main import main

    def call(*args: str) -> tuple[int, str, str]:
        capfd.readouterr()
        rc = main(list(args))
        out, err = capfd.readouterr()
        return rc, out, err

    return call


def pytest_collection_modifyitems(items: list[pytest.Item]) -> None:
    """Mark the tests that drive Chromium (the ``browser`` fixture of
    tests/explore/) ``browser``: ``pytest -m "not browser"`` runs the rest."""
    for item in items:
        if "browser" in getattr(item, "fixturenames", ()):
            item.add_marker(pytest.mark.browser)
