"""Issue 37 item 4 in a real browser: the page places H with "H on f-line"
(``--hc-fraction``), whose tooltip says what the value means."""

from __future__ import annotations

import json
from collections.abc import Iterator

import pytest

from onefold_cad.cli.main import main
from tests.explore.conftest import Page


@pytest.fixture
def tab(browser, server) -> Iterator[Page]:
    context = browser.new_context(viewport={"width": 1400, "height": 860})
    try:
        yield Page(context.new_page(), server.url)
    finally:
        context.close()


def test_h_on_the_f_line_is_a_fraction_the_page_explains_and_sends(tab, capfd):
    """The control shows the template's fraction (0), its tooltip names the
    half f-line R cos(alpha) and the range's ends; 0.6 gives the fold angles
    `onefold solve --hc-fraction 0.6` prints, and so does alpha 80 after it
    (H stays on the f-line: the page sends the fraction, not a length)."""
    page = tab.page
    assert page.locator("#hc_fraction-num").input_value() == "0"
    hint = page.locator("#hc_fraction").locator("xpath=..").get_attribute("title")
    assert "R cos(alpha)" in hint and "-1 and 1" in hint
    for args in (["--hc-fraction", "0.6"], ["--hc-fraction", "0.6", "--alpha", "80"]):
        capfd.readouterr()
        assert main(["solve", *args, "--json"]) == 0
        report = json.loads(capfd.readouterr().out)
        if "--alpha" in args:
            tab.change("#alpha-num", "80")
        else:
            tab.change("#hc_fraction-num", "0.6")
        assert tab.text("#messages") == "none"
        plus = report["fold_angles_deg"]["plus_x"]
        assert f"{plus:.2f}°" in tab.text("#fold-angles")
    assert tab.errors == []
