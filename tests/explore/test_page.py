"""The page in a real browser: Debian's Chromium (software WebGL) driven by playwright."""

from __future__ import annotations

import json
import re
from collections.abc import Iterator
from urllib.parse import urlencode

import ezdxf
import numpy as np
import pytest

from onefold_cad.cli.main import main
from tests.explore.conftest import TIMEOUT_MS, Page, get


@pytest.fixture
def tab(browser, server) -> Iterator[Page]:
    context = browser.new_context(viewport={"width": 1400, "height": 860}, accept_downloads=True)
    try:
        yield Page(context.new_page(), server.url)
    finally:
        context.close()


def test_the_page_loads_and_draws_without_errors_or_outside_requests(tab):
    assert tab.errors == []
    assert tab.foreign == []  # three.js and everything else come from the server: works offline
    pixels = tab.canvas()
    colours = np.unique(pixels.reshape(-1, 3), axis=0)
    assert len(colours) > 100  # shaded form, ground and grid, not a blank canvas
    assert tab.page.locator("#flat svg path.outline").count() == 1
    assert tab.page.locator("#flat svg line.fold").count() == 2
    assert "°" in tab.text("#fold-angles")
    assert tab.text("#messages") == "none"


def test_moving_alpha_changes_the_fold_angles_and_the_picture(tab, server):
    before_text, before = tab.text("#fold-angles"), tab.canvas()
    tab.change("#alpha", "52")
    after_text, after = tab.text("#fold-angles"), tab.canvas()
    assert tab.page.locator("#alpha-num").input_value() == "52"
    assert after_text != before_text
    # the text is the server's fold angle for alpha = 52 (the page computes none)
    _, _, body = get(server, "/api/state?" + urlencode({"alpha": "52"}))
    deg = json.loads(body)["numbers"]["fold_angles"]["plus_x"]["deg"]
    assert f"{deg:.2f}°" in after_text
    changed = np.any(np.abs(after - before) > 8, axis=-1).mean()
    assert changed > 0.01  # more than 1 % of the canvas redrawn differently
    assert tab.errors == []


def test_a_small_move_redraws_the_form_on_the_triangles_it_has(tab, server):
    """alpha 30 -> 31 keeps the mesh's triangles (the same mesh_key): the page asks
    with its key, gets the positions only and draws the new form from them."""
    _, _, body = get(server, "/api/state?" + urlencode({"alpha": "31"}))
    key = json.loads(body)["form"]["mesh_key"]
    before = tab.canvas()
    with tab.page.expect_response(lambda r: "/api/state?" in r.url) as answer:
        tab.change("#alpha-num", "31")
    assert f"mesh={key}" in answer.value.url
    assert answer.value.json()["form"]["indices"] is None
    after = tab.canvas()
    changed = np.any(np.abs(after - before) > 8, axis=-1).mean()
    assert changed > 0.002  # the form moved (it stays where it is, a little larger)
    assert tab.page.locator("#alpha-num").input_value() == "31"
    assert tab.errors == []


def test_a_bad_value_shows_the_clis_message_and_the_page_recovers(tab, capfd):
    capfd.readouterr()
    assert main(["solve", "--alpha", "95"]) == 2
    cli = capfd.readouterr().err.strip().removeprefix("onefold: error: ")
    good = tab.text("#fold-angles")
    tab.change("#alpha-num", "95")
    assert tab.text("#messages") == f"error: {cli}"
    assert "invalid" in (tab.page.locator("#alpha-num").get_attribute("class") or "")
    assert tab.page.locator("#download-dxf").get_attribute("aria-disabled") == "true"
    tab.change("#alpha-num", "31")
    assert tab.text("#messages") == "none"
    assert tab.text("#fold-angles") != good
    assert tab.errors == []


def test_the_dxf_link_downloads_the_current_flat_pattern(tab, tmp_path):
    tab.change("#beta", "36")
    href = tab.page.locator("a#download-dxf").get_attribute("href")
    assert href.startswith("/download/dxf?") and "beta=36" in href
    with tab.page.expect_download(timeout=TIMEOUT_MS) as info:
        tab.page.locator("a#download-dxf").click()
    download = info.value
    assert download.suggested_filename == "patkau-one-fold.dxf"
    path = tmp_path / download.suggested_filename
    download.save_as(path)
    doc = ezdxf.readfile(path)
    assert not doc.audit().has_errors
    assert len(doc.modelspace().query('LWPOLYLINE[layer=="CUT"]')) == 1
    assert tab.errors == []


def test_the_form_s_size_reads_as_onefold_solve_prints_it(tab, capfd):
    """Height, span and footprint (width x depth) of the default design: the
    page's text is the command's. The span is the footprint's width along the
    fold line (what `onefold fit --span` aims at); depth differs from it here,
    so a mix-up of the two would show."""
    capfd.readouterr()
    assert main(["solve"]) == 0
    text = capfd.readouterr().out
    m = re.search(r"height (\S+) mm, span (\S+) mm, footprint (\S+) x (\S+) mm", text)
    height, span, width, depth = m.groups()
    assert width == span != depth
    assert tab.text("#form-height") == f"{height} mm"
    assert tab.text("#form-span") == f"{span} mm"
    assert tab.text("#form-footprint").startswith(f"{width} × {depth} mm, hull area ")
    # the hull's area in m^2 (1 m^2 = 1e6 mm^2), 5 significant digits, not mm^2
    capfd.readouterr()
    assert main(["solve", "--json"]) == 0
    hull = json.loads(capfd.readouterr().out)["resting"]["footprint"]["area"]
    assert tab.text("#form-footprint").endswith(f"hull area {float(f'{hull / 1e6:.5g}'):g} m²")
    assert tab.errors == []
