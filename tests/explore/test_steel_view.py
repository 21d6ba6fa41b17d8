"""The Steel view in Chromium: toggled on, every slider release shows the steel
of the NEW design (its numbers those of simulate() called here), a fast second
release supersedes the first, an error or a busy server is one line, off is
the paper view."""

from __future__ import annotations

from urllib.parse import parse_qsl

import numpy as np
import pytest

from onefold_cad.design import fold_design
from onefold_cad.explore.controls import design_from_params
from onefold_cad.mechanics.simulate import simulate
from tests.explore.conftest import TIMEOUT_MS, get, open_page
from tests.explore.test_simulate import _fmt


def _deviation_text(server, alpha: str) -> str:
    """#sim-deviation for the default template at ``alpha``, from simulate() here."""
    design = design_from_params({"alpha": alpha}, server.templates, server.initial)
    s = simulate(design, fold_design(design), level="coarse", convergence=False).standing
    return f"max {_fmt(s.max_deviation)} mm, rms {_fmt(s.rms_deviation)} mm"


def _stands_text(server, alpha: str) -> str:
    """#sim-stands for the default template at ``alpha`` once its check is done,
    from simulate() here (with its reserve check in line)."""
    design = design_from_params({"alpha": alpha}, server.templates, server.initial)
    s = simulate(design, fold_design(design), level="coarse", convergence=False).standing
    if s.uncertain:
        return f"uncertain: {s.uncertain}"
    return (
        f"yes (tipping margin {_fmt(s.tipping_margin_deg, 3)}°)" if s.stands else f"no: {s.reason}"
    )


def _wait_steel(page, n: int) -> str:
    """Wait for the page's n-th steel answer; the query it shows ('' on an error)."""
    page.locator(f"body[data-steel='{n}']").wait_for(state="attached", timeout=4 * TIMEOUT_MS)
    return page.locator("body").get_attribute("data-steel-query") or ""


def test_the_steel_view_follows_the_sliders(browser, server):
    with open_page(browser, server) as tab:
        page = tab.page
        paper = tab.canvas()
        toggle = page.locator("#steel")
        assert toggle.get_attribute("aria-pressed") == "false"
        toggle.focus()
        page.keyboard.press("Space")  # keyboard: a button
        assert toggle.get_attribute("aria-pressed") == "true"
        assert page.locator("#simulate").is_disabled()  # the view simulates by itself
        shown = dict(parse_qsl(_wait_steel(page, 1)))
        assert shown["template"] == "patkau-one-fold" and shown["alpha"] == "30"
        assert tab.text("#sim-status").startswith("steel of this design in ")
        assert "coarse mesh, the moment law, " in tab.text("#sim-status")
        assert page.locator("#sim-legend").is_visible()
        first = tab.text("#sim-deviation")

        # a slider's release: the page says what it simulates, the steel shown is stale;
        # its steel comes first, "checking…" until its check (held here) answers
        held: list = []
        page.route(
            "**/api/steel/check?**",
            lambda route: (
                held.append(route) if "alpha=33" in route.request.url else route.continue_()
            ),
        )
        with page.expect_response("**/api/steel?**", timeout=4 * TIMEOUT_MS) as answer:
            tab.change("#alpha", "33")
            assert tab.text("#sim-status").startswith("simulating… α 33 (the steel shown")
            assert "stale" in (page.locator("#sim-panel").get_attribute("class") or "")
            page.screenshot(path="/tmp/steelview-stale.png")
        assert dict(parse_qsl(_wait_steel(page, 2)))["alpha"] == "33"
        assert answer.value.json()["ok"] is True
        assert "stale" not in (page.locator("#sim-panel").get_attribute("class") or "")
        assert tab.text("#sim-deviation") == _deviation_text(server, "33") != first
        assert tab.text("#sim-stands").startswith("checking…")
        assert tab.text("#sim-status").endswith("checking whether it stands…")
        page.screenshot(path="/tmp/steelview-on.png")
        for _ in range(500):  # the page asked for the check at once (the route holds it)
            if held:
                break
            page.wait_for_timeout(20)
        checks = int(page.locator("body").get_attribute("data-steel-checked") or 0)
        held[0].continue_()
        page.locator(f"body[data-steel-checked='{checks + 1}']").wait_for(
            state="attached", timeout=4 * TIMEOUT_MS
        )
        page.unroute("**/api/steel/check?**")
        assert tab.text("#sim-stands") == _stands_text(server, "33")
        assert "verdict" in tab.text("#sim-status")
        page.screenshot(path="/tmp/steelview-checked.png")
        steel = tab.canvas()
        h, w = min(paper.shape[0], steel.shape[0]), min(paper.shape[1], steel.shape[1])
        assert np.any(np.abs(steel[:h, :w] - paper[:h, :w]) > 8, axis=-1).mean() > 0.01

        # two fast releases: 34's run is given up for 35's, only 35's is shown
        with page.expect_response(lambda r: "/api/steel?" in r.url and "alpha=34" in r.url) as a34:
            tab.change("#alpha", "34")
            with page.expect_request(lambda r: "/api/steel?" in r.url and "alpha=35" in r.url):
                tab.change("#alpha", "35")
        assert dict(parse_qsl(_wait_steel(page, 3)))["alpha"] == "35"
        assert a34.value.json()["superseded"] is True
        page.wait_for_timeout(300)
        assert page.locator("body").get_attribute("data-steel") == "3"  # 34's never drawn
        assert tab.text("#sim-deviation") == _deviation_text(server, "35")

        # a design that cannot be simulated: one line, in red
        tab.change("#thickness-num", "0")
        assert _wait_steel(page, 4) == ""
        status = tab.text("#sim-status")
        assert status.startswith("cannot simulate this design: thickness: ") and "\n" not in status
        assert "error" in (page.locator("#sim-status").get_attribute("class") or "")
        assert page.locator("#sim-legend").is_hidden()

        # a busy server (the bounded server's 503, plain text): its line, in red
        busy = "the server is busy: too many connections at once, try again"
        page.route(
            "**/api/steel?**",
            lambda route: route.fulfill(
                status=503, body=busy + "\n", content_type="text/plain; charset=utf-8"
            ),
        )
        tab.change("#thickness-num", "3")
        assert _wait_steel(page, 5) == ""
        assert tab.text("#sim-status") == busy
        assert "error" in (page.locator("#sim-status").get_attribute("class") or "")
        page.unroute("**/api/steel?**")

        # off: the paper view, Simulate again
        toggle.click()
        assert toggle.get_attribute("aria-pressed") == "false"
        assert page.locator("#simulate").is_enabled() and page.locator("#sim-legend").is_hidden()
        assert tab.text("#sim-deviation") == "–"
        assert tab.text("#sim-status").startswith("steel under its own weight")
        page.screenshot(path="/tmp/steelview-off.png")
        # the browser logs the 503 it was given, nothing else
        assert [e for e in tab.errors if "status of 503" not in e] == [] and tab.foreign == []


@pytest.fixture(autouse=True)
def _fresh_designs(server):
    server.design_of.cache_clear()


def test_a_check_the_server_no_longer_holds_asks_for_the_steel_again(browser, server):
    """The steel of alpha 30 is shown, its check held (a Playwright route);
    meanwhile another client's steel request (alpha 31) makes 31 the server's
    last steel simulation; let go, the check answers ``gone`` and the page
    asks for 30's steel again, then shows its verdict: never a verdict of
    another design, never "checking…" for good."""
    with open_page(browser, server) as tab:
        page = tab.page
        held: list = []
        page.route("**/api/steel/check?**", lambda route: held.append(route))
        page.locator("#steel").click()
        assert dict(parse_qsl(_wait_steel(page, 1)))["alpha"] == "30"
        for _ in range(500):  # the page asked for the check at once (the route holds it)
            if held:
                break
            page.wait_for_timeout(20)
        page.unroute("**/api/steel/check?**")
        assert tab.text("#sim-stands").startswith("checking…")
        status, _, _ = get(server, "/api/steel?alpha=31")  # another client
        assert status == 200
        held[0].continue_()
        assert dict(parse_qsl(_wait_steel(page, 2)))["alpha"] == "30"  # asked again
        page.locator("body[data-steel-checked='1']").wait_for(
            state="attached", timeout=4 * TIMEOUT_MS
        )
        assert tab.text("#sim-stands") == _stands_text(server, "30")
        assert tab.errors == [] and tab.foreign == []
