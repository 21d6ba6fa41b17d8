"""The Simulate button and /api/simulate: one coarse simulation, clicked in Chromium."""

from __future__ import annotations

import base64
import json
from pathlib import Path
from urllib.parse import parse_qsl, urlencode, urlsplit

import numpy as np
import pytest

from onefold_cad.explore.controls import PAGE_FLAGS
from onefold_cad.export.simulation.colour_scale import (
    DEVIATION_STOPS,
    deviation_range,
    ramp,
    to_uint8,
)
from tests.explore.conftest import TIMEOUT_MS, get, open_page


def _fmt(x: float, digits: int = 4) -> str:
    """A number as the page prints it (JS ``String(Number(x.toPrecision(d)))``)."""
    text = f"{float(f'{x:.{digits}g}'):.{digits + 2}g}"
    return text


def _decode(mesh: dict) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    def arr(key: str, dtype: str, width: int) -> np.ndarray:
        return np.frombuffer(base64.b64decode(mesh[key]), dtype=dtype).reshape(-1, width)

    kind = {"uint16": "<u2", "uint32": "<u4"}[mesh["index_type"]]
    return (
        arr("designed", "<f4", 3),
        arr("positions", "<f4", 3),
        arr("indices", kind, 3),
        arr("colours", "u1", 3),
    )


def _simulate(server, query: str = "") -> tuple[int, dict]:
    status, headers, body = get(server, f"/api/simulate?{query}")
    assert headers["content-type"] == "application/json"
    return status, json.loads(body)


@pytest.mark.parametrize(
    ("query", "error"),
    [
        ({"model": "paper"}, "cannot simulate this design: model: simulate needs the exact model"),
        ({"thickness": "0"}, "cannot simulate this design: thickness: simulate needs a sheet"),
        ({"alpha": "95"}, "--alpha: must be in (0, 90) deg, got 95"),
    ],
    ids=["paper", "no-thickness", "bad-value"],
)
def test_a_design_that_cannot_be_simulated_answers_one_line(server, query, error):
    status, data = _simulate(server, urlencode(query))
    assert status == 200 and data["ok"] is False
    assert data["error"].startswith(error) and "\n" not in data["error"]


def test_simulate_is_refused_like_every_route(server):
    assert get(server, "/api/simulate", {"Host": "evil.example"})[0] == 403
    assert get(server, "/api/simulate", {"Sec-Fetch-Site": "cross-site"})[0] == 403
    assert get(server, "/api/simulate", method="POST")[0] == 405
    assert get(server, "/api/simulate?nonsense=1")[0] == 400


def test_an_unexpected_failure_is_an_error_line(server, monkeypatch, capsys):
    import onefold_cad.explore.server as srv

    def broken(*args, **kwargs):
        raise RuntimeError("boom")

    monkeypatch.setattr(srv, "simulation_state", broken)
    status, data = _simulate(server)
    assert status == 500 and data == {"ok": False, "error": "internal error (RuntimeError: boom)"}
    assert "RuntimeError: boom" in capsys.readouterr().err


def _check_answer(data: dict) -> None:
    """The answer of the default design: the forms on one mesh, the colours the scale's."""
    assert data["ok"] and data["level"] == "coarse" and data["units"] == "mm"
    mesh, n = data["mesh"], data["numbers"]
    designed, standing, faces, colours = _decode(mesh)
    assert mesh["form"] == "standing" and n["stands"] is True
    assert designed.shape == standing.shape == (mesh["vertex_count"], 3) == (n["nodes"], 3)
    assert faces.shape == (mesh["triangle_count"], 3) and faces.max() < len(designed)
    size = float(np.ptp(designed, axis=0).max())
    assert abs(designed[:, 2].min()) <= 1e-6 * size and abs(standing[:, 2].min()) <= 1e-6 * size
    assert float(standing[:, 2].max()) == pytest.approx(n["height"], rel=1e-6)
    # the deviation: the largest node's distance; its colour the scale's top
    dev = np.linalg.norm(standing - designed, axis=1)  # at least the surface distance ...
    assert n["max_deviation"] <= dev.max() * (1 + 1e-6)
    scale = data["scale"]
    assert scale["label"] == "deviation from the design (mm)"
    assert scale["min"] == 0.0 and scale["max"] == pytest.approx(n["max_deviation"])
    assert tuple(scale["stops"]) == DEVIATION_STOPS
    top = to_uint8(ramp(np.array([scale["max"]]), *deviation_range(np.array([scale["max"]]))))
    assert (np.all(colours == top, axis=1)).sum() >= 1
    for key in ("rms_deviation", "span", "springback_max_deviation", "plastic_area_share"):
        assert n[key] is not None and n[key] > 0
    assert n["max_stress_MPa"] > 0 and n["yield_stress_MPa"] == 215.0


def test_the_simulate_button_shows_the_standing_form_and_clears_on_a_change(browser, server):
    """The round trip: click Simulate, the page asks /api/simulate with the state's
    query, draws the coloured standing form over the design with its legend and
    numbers; a control change clears it; a paper model answers one error line."""
    with open_page(browser, server) as tab:
        page = tab.page
        assert page.locator("#simulate").is_enabled()
        assert page.locator("#sim-legend").is_hidden()
        before = tab.canvas()
        with page.expect_response("**/api/simulate?**", timeout=4 * TIMEOUT_MS) as answer:
            page.locator("#simulate").click()
        page.locator("body[data-simulations='1']").wait_for(state="attached")
        data = answer.value.json()
        _check_answer(data)
        query = dict(parse_qsl(urlsplit(answer.value.url).query, keep_blank_values=True))
        assert query["template"] == "patkau-one-fold" and set(query) - {"template"} <= set(
            PAGE_FLAGS
        )
        n = data["numbers"]
        assert tab.text("#sim-deviation") == (
            f"max {_fmt(n['max_deviation'])} mm, rms {_fmt(n['rms_deviation'])} mm"
        )
        # patkau on the coarse mesh stands without the reserve a plain yes needs
        assert n["uncertain"] and tab.text("#sim-stands") == f"uncertain: {n['uncertain']}"
        assert tab.text("#sim-size") == f"{_fmt(n['height'])} mm · {_fmt(n['span'])} mm"
        assert _fmt(n["max_stress_MPa"]) in tab.text("#sim-stress")
        # onefold simulate's law, J2: a stress the steel can be in, hardened
        # past yield (215 + 507 eps_p MPa, eps_p about 0.3 by H), not the
        # moment law's elastic estimate of 25 times yield
        assert n["law"] == "j2" and 1 < n["utilisation"] < 2
        assert tab.text("#sim-stress").endswith("the flow stress, hardened past yield)")
        assert (
            tab.text("#sim-springback") == f"max deviation {_fmt(n['springback_max_deviation'])} mm"
        )
        assert page.locator("#sim-legend").is_visible()
        assert "deviation from the design (mm)" in tab.text("#sim-legend")
        assert tab.text("#sim-max") == _fmt(data["scale"]["max"])
        assert tab.text("#sim-status").startswith("simulated in ")
        assert "coarse mesh, J2 through the thickness, " in tab.text("#sim-status")
        after = tab.canvas()
        # the panel's numbers and warnings may change the view's height: compare
        # the part both screenshots share
        h, w = min(before.shape[0], after.shape[0]), min(before.shape[1], after.shape[1])
        assert np.any(np.abs(after[:h, :w] - before[:h, :w]) > 8, axis=-1).mean() > 0.01
        r, g, b = after[..., 0], after[..., 1], after[..., 2]
        assert ((b - g > 30) & (r - g > 15)).sum() > 200  # viridis's purples: the scale's low end

        tab.change("#alpha-num", "31")  # the design changed: the simulation goes
        assert page.locator("#sim-legend").is_hidden() and tab.text("#sim-deviation") == "–"
        assert tab.text("#sim-status").startswith("steel under its own weight")

        n_updates = tab.updates()
        page.locator("#model").select_option("paper")
        tab.wait_for_update(n_updates + 1)
        page.locator("#simulate").click()
        page.locator("body[data-simulations='2']").wait_for(state="attached")
        status = tab.text("#sim-status")
        assert status.startswith("cannot simulate this design: model: ") and "\n" not in status
        assert "error" in (page.locator("#sim-status").get_attribute("class") or "")
        assert page.locator("#sim-legend").is_hidden()
        assert tab.errors == [] and tab.foreign == []


def test_the_cones_control_simulates_cones_formed_past_their_springback(browser, server, tmp_path):
    """'cones: past their springback' sends cone_forming=compensated: Simulate
    answers simulate's J2 of such cones (a springback of millimetres, against
    some 440 mm formed to the design), the status names it, and the Cones CSV
    download gives the radii to form to."""
    with open_page(browser, server) as tab:
        page = tab.page
        n_updates = tab.updates()
        page.locator("#cone_forming").select_option("compensated")
        tab.wait_for_update(n_updates + 1)
        with page.expect_response("**/api/simulate?**", timeout=4 * TIMEOUT_MS) as answer:
            page.locator("#simulate").click()
        page.locator("body[data-simulations='1']").wait_for(state="attached")
        query = dict(parse_qsl(urlsplit(answer.value.url).query, keep_blank_values=True))
        assert query["cone_forming"] == "compensated"
        n = answer.value.json()["numbers"]
        assert (n["law"], n["cone_forming"]) == ("j2", "compensated")
        assert n["springback_max_deviation"] < 20.0  # mm: the radii leave the design's curvature
        status = tab.text("#sim-status")
        assert "J2 through the thickness, cones formed past their springback, " in status
        page.screenshot(path=str(tmp_path / "cones-compensated.png"))
        # the Steel view forms such cones with J2 too, and its reserve check
        # (left for after the form) gives the verdict Simulate gave
        page.locator("#steel").click()
        page.locator("body[data-steel-checked='1']").wait_for(
            state="attached", timeout=4 * TIMEOUT_MS
        )
        assert "J2 through the thickness, cones formed past their springback, " in tab.text(
            "#sim-status"
        )
        assert tab.text("#sim-stands") == f"uncertain: {n['uncertain']}"
        page.locator("#steel").click()
        with page.expect_download() as dl:
            page.locator("#download-cones").click()
        assert dl.value.suggested_filename == "patkau-one-fold-cones.csv"
        head, first = Path(dl.value.path()).read_text(encoding="utf-8").splitlines()[:2]
        assert head.startswith("side,ruling_deg") and first.startswith("+y,")
