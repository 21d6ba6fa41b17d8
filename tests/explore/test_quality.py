"""Drag frames (static/quality.js) in Chromium: reduced while a drag goes on and full
frames are slow here, then the full frame of the state, as a fresh page draws it."""

from __future__ import annotations

import json
from collections.abc import Iterator
from pathlib import Path
from urllib.parse import urlencode

import numpy as np
import pytest
from PIL import Image

from tests.explore.conftest import TIMEOUT_MS, Page, get

#: quality.js's SLOW_MS and DRAG_SCALE, as its comment states them.
SLOW_MS = 16
DRAG_SCALE = 0.5

# Records every update's frame quality and drawing-buffer width (the update's
# own, as drawn: sampled when the event fires, the canvas may already show the
# full frame the settle timer drew after it on a loaded machine), and every
# settled frame with the canvas's width then.
RECORD = """() => {
  window.__frames = [];
  const canvas = document.getElementById('view');
  for (const name of ['explore:updated', 'explore:settled']) {
    window.addEventListener(name, (e) => window.__frames.push({
      event: name, quality: e.detail.quality, width: e.detail.width ?? canvas.width }));
  }
}"""
READOUT = ["#fold-angles", "#apex-height", "#form-height", "#form-span", "#form-footprint",
           "#flat-size", "#relief-hole", "#angle-error", "#messages"]  # fmt: skip


@pytest.fixture
def context(browser) -> Iterator[object]:
    ctx = browser.new_context(viewport={"width": 1400, "height": 860}, accept_downloads=True)
    try:
        yield ctx
    finally:
        ctx.close()


def _until(tab: Page, js: str) -> None:
    """Wait until the page's ``js`` (a function) returns true (wait_for_function
    would evaluate a string: the page's CSP forbids it)."""
    for _ in range(TIMEOUT_MS // 20):
        if tab.page.evaluate(js):
            return
        tab.page.wait_for_timeout(20)
    raise AssertionError(f"timed out waiting for {js}")


def _slow(tab: Page) -> bool:
    """Whether the page found its full frames slow (the median of the last three
    GPU times it measured, ms, over SLOW_MS); it has measured some."""
    _until(tab, "() => document.getElementById('view').dataset.fullFrameMs?.split(' ').length >= 3")
    ms = [float(x) for x in tab.page.locator("#view").get_attribute("data-full-frame-ms").split()]
    return float(np.median(ms[-3:])) > SLOW_MS


def _settled(tab: Page) -> None:
    _until(
        tab,
        "() => document.getElementById('view').dataset.quality === 'full' && "
        "window.__frames.some((f) => f.event === 'explore:settled')",
    )


def _save(pixels: np.ndarray, path: Path) -> None:
    Image.fromarray(pixels.astype(np.uint8)).save(path)


def test_the_decision_is_the_median_of_the_last_three_full_frames(context, server):
    tab = Page(context.new_page(), server.url)
    got = tab.page.evaluate(
        """async () => {
      const { slowFrames } = await import('/static/quality.js');
      return [[], [5], [30], [5, 30, 40], [30, 5, 6], [100, 100, 5, 6, 7], [16, 16, 16]]
        .map((ms) => slowFrames(ms));
    }"""
    )
    assert got == [False, False, True, True, False, False, False]


def test_a_slider_drag_shows_reduced_frames_then_the_full_frame_of_its_state(
    context, server, tmp_path
):
    """A mouse drag of the alpha slider (many input events, then change): while it
    goes on, the updates are drawn at half the pixel ratio (full frames take more
    than 16 ms in software GL); it ends with a full frame identical in every pixel
    to the one a fresh page draws for the same values, and the numbers, messages
    and downloads of the final state."""
    tab = Page(context.new_page(), server.url)
    full_width = tab.page.evaluate("document.getElementById('view').width")
    slow = _slow(tab)
    tab.page.evaluate(RECORD)
    box = tab.page.locator("#alpha").bounding_box()
    y = box["y"] + box["height"] / 2
    x0 = box["x"] + box["width"] * float(tab.page.locator("#alpha-num").input_value()) / 90.0
    tab.page.mouse.move(x0, y)
    tab.page.mouse.down()
    for k in range(1, 7):
        tab.page.mouse.move(x0 + 6 * k, y)
        tab.page.wait_for_timeout(40)
    tab.page.mouse.up()
    if slow:
        _settled(tab)
    else:
        tab.page.wait_for_timeout(500)
    _until(tab, "() => !document.getElementById('status').textContent.includes('solv')")
    frames = tab.page.evaluate("window.__frames")
    updates = [f for f in frames if f["event"] == "explore:updated"]
    assert len(updates) >= 2  # several inputs, each its update (the latest values win)
    if slow:
        reduced = [f for f in updates if f["quality"] == "drag"]
        assert reduced, frames
        assert all(f["width"] == round(full_width * DRAG_SCALE) for f in reduced)
        assert frames[-1]["quality"] == "full" and frames[-1]["width"] == full_width
    else:  # a fast GPU: nothing changes
        assert all(f["quality"] == "full" and f["width"] == full_width for f in frames)
    assert tab.page.evaluate("document.getElementById('view').width") == full_width
    alpha = tab.page.locator("#alpha-num").input_value()
    assert alpha != "30"
    dragged = tab.canvas()
    readout = [tab.text(s) for s in READOUT]

    fresh = Page(context.new_page(), server.url)
    fresh.change("#alpha-num", alpha)
    assert fresh.page.locator("#view").get_attribute("data-quality") == "full"
    again = fresh.canvas()
    _save(dragged, tmp_path / "dragged_settled.png")
    _save(again, tmp_path / "fresh.png")
    assert dragged.shape == again.shape
    assert np.array_equal(dragged, again)
    assert readout == [fresh.text(s) for s in READOUT]
    _, _, body = get(server, "/api/state?" + urlencode({"alpha": alpha}))
    deg = json.loads(body)["numbers"]["fold_angles"]["plus_x"]["deg"]
    assert f"{deg:.2f}°" in readout[0]

    href = tab.page.locator("a#download-json").get_attribute("href")
    assert f"alpha={alpha}" in href
    with tab.page.expect_download(timeout=TIMEOUT_MS) as info:
        tab.page.locator("a#download-json").click()
    path = tmp_path / info.value.suggested_filename
    info.value.save_as(path)
    assert json.loads(path.read_text())["inputs"]["frame"]["alpha"] == float(alpha)
    assert tab.errors == [] and fresh.errors == []


def test_orbiting_draws_reduced_frames_until_the_release(context, server, tmp_path):
    """While the mouse orbits the view (held down), the frames are reduced: the
    same picture at half the resolution; the release draws it in full."""
    tab = Page(context.new_page(), server.url)
    full_width = tab.page.evaluate("document.getElementById('view').width")
    slow = _slow(tab)
    tab.page.evaluate(RECORD)
    box = tab.page.locator("#view").bounding_box()
    cx, cy = box["x"] + box["width"] / 2, box["y"] + box["height"] / 2
    tab.page.mouse.move(cx, cy)
    tab.page.mouse.down()
    tab.page.mouse.move(cx + 40, cy, steps=4)
    want = "drag" if slow else "full"
    _until(tab, f"() => document.getElementById('view').dataset.quality === '{want}'")
    held = tab.canvas()
    during = tab.page.evaluate("[document.getElementById('view').width, "
                               "document.getElementById('view').dataset.quality]")  # fmt: skip
    tab.page.mouse.up()
    if slow:
        _settled(tab)
    released = tab.canvas()
    _save(held, tmp_path / "orbit_held.png")
    _save(released, tmp_path / "orbit_released.png")
    assert tab.page.evaluate("document.getElementById('view').width") == full_width
    assert tab.page.locator("#view").get_attribute("data-quality") == "full"
    if slow:
        assert during == [round(full_width * DRAG_SCALE), "drag"]
        changed = np.any(np.abs(held - released) > 8, axis=-1).mean()
        assert 0.001 < changed < 0.2  # the same picture, its edges softer
    else:
        assert during == [full_width, "full"]
    assert tab.errors == []
