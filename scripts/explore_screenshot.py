"""Screenshots of ``onefold explore`` for the README and docs/explore.md.

    .venv/bin/python scripts/explore_screenshot.py [--outdir docs/images]

Starts the explorer in this process (127.0.0.1, a free port), opens it in
Debian's Chromium (playwright, software WebGL) at 1500 x 880 and saves:

- ``explore.png``: the default template as it opens;
- ``explore-star.png``: the star-polygon template after moving alpha to 40;
- ``explore-error.png``: the default template with alpha typed as 95 (the
  message, the marked control, the last good form dimmed);
- ``explore-simulate.png``: the default template after Simulate (the standing
  steel sheet coloured by its deviation over the translucent design, the
  legend and the numbers);
- ``explore-steel-stale.png``: then the Steel view on and alpha's slider
  released at 33, while its steel is simulated (the steel of alpha 30 marked
  stale over the new design);
- ``explore-steel.png``: the steel of alpha 33 when it arrives.
"""

from __future__ import annotations

import argparse
import sys
import threading
from pathlib import Path

from onefold_cad.explore.server import make_server

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "benchmarks"))

from chromium import CHROMIUM, CHROMIUM_ARGS  # noqa: E402


def _wait(page, n: int) -> None:
    page.locator(f"body[data-updates='{n}']").wait_for(state="attached", timeout=60_000)


def main(argv: list[str] | None = None) -> int:
    from playwright.sync_api import sync_playwright

    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--outdir", type=Path, default=ROOT / "docs" / "images")
    args = ap.parse_args(argv)
    server = make_server(None, port=0)
    thread = threading.Thread(target=server.serve_forever, daemon=True)
    thread.start()
    try:
        with sync_playwright() as pw:
            browser = pw.chromium.launch(executable_path=CHROMIUM, args=CHROMIUM_ARGS)
            page = browser.new_page(viewport={"width": 1500, "height": 880})
            page.goto(server.url)
            _wait(page, 1)
            page.screenshot(path=args.outdir / "explore.png")

            page.locator("#template").select_option("star-polygon")
            _wait(page, 2)
            page.locator("#alpha").fill("40")
            _wait(page, 3)
            page.screenshot(path=args.outdir / "explore-star.png")

            page.locator("#template").select_option("patkau-one-fold")
            _wait(page, 4)
            page.locator("#alpha-num").fill("95")
            _wait(page, 5)
            page.screenshot(path=args.outdir / "explore-error.png")

            page.locator("#alpha-num").fill("30")
            _wait(page, 6)
            page.locator("#simulate").click()
            page.locator("body[data-simulations='1']").wait_for(state="attached", timeout=300_000)
            page.screenshot(path=args.outdir / "explore-simulate.png")

            page.locator("#steel").click()
            steel = page.locator("body[data-steel='1']")
            steel.wait_for(state="attached", timeout=300_000)
            page.locator("#alpha").fill("33")
            page.locator("#sim-panel.stale").wait_for(state="attached", timeout=60_000)
            page.screenshot(path=args.outdir / "explore-steel-stale.png")
            steel = page.locator("body[data-steel='2']")
            steel.wait_for(state="attached", timeout=300_000)
            page.screenshot(path=args.outdir / "explore-steel.png")
            browser.close()
    finally:
        server.shutdown()
        server.server_close()
    for name in ("", "-star", "-error", "-simulate", "-steel-stale", "-steel"):
        print(args.outdir / f"explore{name}.png")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
