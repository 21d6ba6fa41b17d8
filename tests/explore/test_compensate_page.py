"""The Compensate button in Chromium: a real compensation (a 20 mm sheet on the
coarse mesh, about 20 s of CPU) started from the keyboard, its progress, its
result equal to compensate() called here with the explorer's settings, the
sliders moved to the compensated values and back; Cancel stops a run."""

from __future__ import annotations

import json
import math
import re
from urllib.parse import parse_qsl, urlsplit

import pytest

from onefold_cad.compensate.parallel import Evaluator
from onefold_cad.compensate.run import compensate
from onefold_cad.compensate.target import make_target
from onefold_cad.explore.controls import design_from_params
from tests.explore.conftest import TIMEOUT_MS, get, open_page
from tests.explore.test_simulate import _fmt

pytestmark = pytest.mark.browser

_ETA = re.compile(r", ETA .*$")


def _press(page, selector: str) -> None:
    """Press a button from the keyboard."""
    page.locator(selector).focus()
    page.keyboard.press("Enter")


def _reference(server, params: dict[str, str]):
    """compensate() called here as the explorer runs it: coarse search of the
    sliders' knobs (alpha, beta, h_c: no crease overbend), coarse checks
    without the convergence check, in this process."""
    design = design_from_params(params, server.templates, server.initial)
    lines: list[str] = []
    with Evaluator(1) as ev:
        c = compensate(design, make_target(design, "design"), ev, lines.append,
                       coarse="coarse", fine="coarse", check=False,
                       knobs=("alpha", "beta", "h_c"))  # fmt: skip
    assert c.found.knobs == ("alpha", "beta", "h_c")
    return c, lines


def _same(got, want) -> None:
    if want is None or (isinstance(want, float) and not math.isfinite(want)):
        assert got is None
    else:
        assert got == pytest.approx(want, rel=1e-6, abs=1e-9)


def test_compensate_in_the_page(browser, server):
    with open_page(browser, server, height=980) as tab:
        page = tab.page
        tab.change("#thickness-num", "20")
        button = page.locator("#compensate")
        assert button.is_visible() and button.is_enabled()
        assert page.locator("#comp-cancel").is_hidden()

        # Cancel: the run stops, the page says so, the button is back
        _press(page, "#compensate")
        page.locator("body[data-compensation='running']").wait_for(state="attached")
        page.locator("#comp-status", has_text="simulations").wait_for()
        assert page.locator("#comp-cancel").is_visible() and button.is_disabled()
        _press(page, "#comp-cancel")
        page.locator("body[data-compensation='cancelled']").wait_for(
            state="attached", timeout=TIMEOUT_MS
        )
        assert tab.text("#comp-status").startswith("compensation cancelled after ")
        assert button.is_enabled() and page.locator("#comp-cancel").is_hidden()
        cancelled = int(page.locator("body").get_attribute("data-compensation-job") or 0)
        assert _json(server, f"/api/compensate/progress?job={cancelled}")["state"] == "cancelled"

        # a whole run: progress with the ETA, then the result and the sliders
        with page.expect_request("**/api/compensate/start?**") as asked:
            _press(page, "#compensate")
        params = dict(parse_qsl(urlsplit(asked.value.url).query))
        assert params["thickness"] == "20" and params["alpha"] == "30"
        page.locator("#comp-status", has_text="ETA").wait_for(timeout=TIMEOUT_MS)
        progress = tab.text("#comp-status")
        assert progress.startswith("compensating (coarse preview) patkau-one-fold α 30, β 30")
        page.screenshot(path="/tmp/compaction-progress.png")
        # the sliders stay usable and do not cancel: the job is the design as pressed
        tab.change("#width-num", "3000")
        running = page.locator("body").get_attribute("data-compensation-job")
        assert _json(server, f"/api/compensate/progress?job={running}")["state"] != "cancelled"
        n = tab.updates()
        page.locator("body[data-compensation='done']").wait_for(
            state="attached", timeout=4 * TIMEOUT_MS
        )
        tab.wait_for_update(n + 1)  # the compensated design's state drawn
        page.screenshot(path="/tmp/compaction-done.png")
        job = int(page.locator("body").get_attribute("data-compensation-job") or 0)
        done = _json(server, f"/api/compensate/progress?job={job}")
        assert done["state"] == "done" and done["design"] == params

        # the job's numbers are compensate()'s
        c, lines = _reference(server, params)
        r = done["result"]
        for key in ("before", "after"):
            want = getattr(c, key).to_data()
            for k, v in want.items():
                _same(r[key][k], v)
        f = c.compensated.frame
        for k in ("alpha", "beta", "h_c"):
            _same(r["compensated"][k], getattr(f, k))
        assert r["compensated"]["overbend"] == 0.0  # no slider to load an overbend into
        for got, want in zip(r["crease"], c.crease, strict=True):
            assert got["half"] == want["half"] and got["bend"] == want["bend"]
            _same(got["fold_to_deg"], want["fold_to_deg"])
            _same(got["after_springback_deg"], want["after_springback_deg"])
        assert r["simulations"] == c.simulations == done["simulations"]
        assert r["reached"] == c.reached and r["cpu_s"] > 0
        assert [_ETA.sub("", t) for t in done["lines"]] == [_ETA.sub("", t) for t in lines]
        # the verdict's numbers are printed to 2 to 4 digits: equal text
        assert r["verdict"] == c.verdict

        # the page: the sliders hold the compensated values, the panel before -> after
        values = r["values"]
        start = {k: v for k, v in params.items() if k != "template"}
        assert values == {**start, **{k: values[k] for k in ("alpha", "beta", "hc_fraction")}}
        assert r["start_values"] == start
        for k, text in values.items():  # the job's design (width 3048), the compensated fold
            plain = k in ("model", "divisions", "radius", "polygon", "cone_forming")
            assert page.locator(f"#{k}" if plain else f"#{k}-num").input_value() == text
        assert values["width"] == "3048"
        assert float(values["alpha"]) == pytest.approx(f.alpha, rel=1e-12)
        assert float(values["beta"]) == pytest.approx(f.beta, rel=1e-12)
        half = f.radius * math.cos(math.radians(f.alpha))
        assert float(values["hc_fraction"]) == pytest.approx(f.h_c / half, rel=1e-9, abs=1e-15)
        panel = tab.text("#comp-result")
        b, a = c.before, c.after
        assert f"{_fmt(b.max_deviation)} mm → {_fmt(a.max_deviation)} mm" in panel
        assert f"{_fmt(b.rms_deviation)} mm → {_fmt(a.rms_deviation)} mm" in panel
        assert f"{_fmt(b.height)} mm → {_fmt(a.height)} mm" in panel
        assert f"{_fmt(b.span)} mm → {_fmt(a.span)} mm" in panel
        assert c.verdict in panel
        # what simulate warns of the compensated steel, each in the panel
        assert r["warnings"] == list(c.after_sim.warnings)
        assert any("the springback is underestimated" in w for w in r["warnings"])
        flat = " ".join(panel.split())
        for w in c.after_sim.warnings:
            assert " ".join(w.split()) in flat
        assert r["law"] == "moment"  # cones formed to the design: the page's preview law
        assert ("coarse preview with the moment law: onefold compensate's search and checks on "
                "the coarse mesh") in panel  # fmt: skip
        assert tab.text("#comp-status").startswith("compensated (coarse preview) in ")
        assert tab.text("#comp-status").endswith("the sliders hold the compensated values")

        # back to the uncompensated values, and again to the compensated ones
        n = tab.updates()
        _press(page, "#comp-back")
        tab.wait_for_update(n + 1)
        assert page.locator("#alpha-num").input_value() == "30"
        assert page.locator("#hc_fraction-num").input_value() == "0"
        assert tab.text("#comp-back") == "Load compensated"
        assert tab.text("#comp-status").endswith("the sliders hold the uncompensated values")
        page.screenshot(path="/tmp/compaction-back.png")
        n = tab.updates()
        _press(page, "#comp-back")
        tab.wait_for_update(n + 1)
        assert page.locator("#alpha-num").input_value() == values["alpha"]
        assert tab.errors == [] and tab.foreign == []


def _json(server, target: str) -> dict:
    status, _, body = get(server, target)
    assert status == 200, body
    return json.loads(body)


def test_a_design_without_steel_data_is_one_line_in_the_page(browser, server):
    with open_page(browser, server, height=900) as tab:
        page = tab.page
        n = tab.updates()
        page.locator("#model").select_option("paper")
        tab.wait_for_update(n + 1)
        _press(page, "#compensate")
        page.locator("body[data-compensation='refused']").wait_for(state="attached")
        status = tab.text("#comp-status")
        assert status.startswith("cannot compensate this design: model: simulate needs the exact")
        assert "error" in (page.locator("#comp-status").get_attribute("class") or "")
        assert page.locator("#compensate").is_enabled()
        page.screenshot(path="/tmp/compaction-refused.png")
