"""How fast the explorer's page follows a slider, in a real browser on this machine.

Starts ``onefold explore TEMPLATE --no-browser --port 0`` (its own process),
opens the page in Debian's Chromium (playwright, software WebGL) and moves a
slider as a user would (sets the value, fires ``input``). Each update is
timed inside the page, from the slider's ``input`` event to the first
animation frame after the new numbers, flat pattern and 3D form are drawn
(the page's ``explore:updated`` event). Interleaved with each move, round by
round in alternating order, the same state is fetched over HTTP from Python
(no browser): the server's share of the time. Prints medians with their
spread (25th and 75th percentile) and the worst move; asserts nothing.

Run from the repository root::

    .venv/bin/python benchmarks/bench_explore.py [--moves 40] [--only NAME ...]
"""

from __future__ import annotations

import argparse
import http.client
import subprocess
import sys
import time
from pathlib import Path
from urllib.parse import urlencode

sys.path.insert(0, str(Path(__file__).resolve().parent))

from interleave import stats_of  # noqa: E402

CHROMIUM_ARGS = [
    "--headless",
    "--no-sandbox",
    "--disable-gpu",
    "--disable-quic",
    "--no-first-run",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
    "--use-angle=swiftshader",
]
TEMPLATES = ["patkau-one-fold", "table1-row4", "star-polygon"]
CRITERION_MS = 300.0

# In the page: move slider `id` to `value`, resolve with the milliseconds from
# the input event to the frame after the update was drawn.
MOVE = """async ([id, value]) => {
  const el = document.getElementById(id);
  const done = new Promise((resolve) => window.addEventListener(
    'explore:updated', (e) => resolve(e.detail), { once: true }));
  const t0 = performance.now();
  el.value = value;
  el.dispatchEvent(new Event('input', { bubbles: true }));
  const d = await done;
  return { ms: d.done - t0, ok: d.ok };
}"""


def start_server(template: str) -> tuple[subprocess.Popen[str], int]:
    """``onefold explore TEMPLATE --no-browser --port 0`` and the port it printed."""
    exe = Path(sys.executable).with_name("onefold")
    proc = subprocess.Popen(
        [str(exe), "explore", template, "--no-browser", "--port", "0"],
        stderr=subprocess.PIPE,
        text=True,
    )
    assert proc.stderr is not None
    line = proc.stderr.readline()
    if "http://127.0.0.1:" not in line:
        proc.kill()
        raise SystemExit(f"onefold explore did not start: {line}")
    port = int(line.split("http://127.0.0.1:")[1].split("/")[0])
    return proc, port


def fetch_state(port: int, query: str) -> float:
    """Wall milliseconds of one GET /api/state?query (server compute and transfer)."""
    conn = http.client.HTTPConnection("127.0.0.1", port, timeout=60)
    t0 = time.perf_counter()
    conn.request("GET", f"/api/state?{query}", headers={"Host": f"127.0.0.1:{port}"})
    res = conn.getresponse()
    res.read()
    ms = 1e3 * (time.perf_counter() - t0)
    conn.close()
    if res.status != 200:
        raise SystemExit(f"state request failed: {res.status}")
    return ms


def values(page, slider: str, n: int) -> list[str]:
    """``n`` distinct values within 10 % of the slider's range of its current value
    (inside the range), back and forth: small moves, as a hand drags."""
    lo = float(page.locator(f"#{slider}").get_attribute("min"))
    hi = float(page.locator(f"#{slider}").get_attribute("max"))
    now = float(page.locator(f"#{slider}-num").input_value())
    a, b = max(lo, now - 0.1 * (hi - lo)), min(hi, now + 0.1 * (hi - lo))
    out = []
    for i in range(n):
        s = (i % 20) / 19.0
        s = s if (i // 20) % 2 == 0 else 1.0 - s
        out.append(f"{a + (b - a) * s:.6g}")
    return out


def bench_template(browser, template: str, moves: int) -> list[str]:
    proc, port = start_server(template)
    rows = []
    try:
        page = browser.new_page(viewport={"width": 1400, "height": 860}, bypass_csp=True)
        page.goto(f"http://127.0.0.1:{port}/")
        page.locator("body[data-updates='1']").wait_for(state="attached", timeout=60_000)
        for slider in ("alpha", "beta", "hc"):
            vals = values(page, slider, moves + 3)
            base = {k: page.locator(f"#{k}-num").input_value() for k in ("alpha", "beta", "hc")}
            for v in vals[:3]:  # warm up
                page.evaluate(MOVE, [slider, v])
            browser_ms, http_ms = [], []
            for i, v in enumerate(vals[3:]):
                query = urlencode({**base, slider: v})
                steps = ("page", "http") if i % 2 == 0 else ("http", "page")
                for step in steps:
                    if step == "page":
                        r = page.evaluate(MOVE, [slider, v])
                        if not r["ok"]:
                            raise SystemExit(f"{template}: {slider}={v} gave an error state")
                        browser_ms.append(r["ms"])
                    else:
                        http_ms.append(fetch_state(port, query))
            b, h = stats_of(browser_ms), stats_of(http_ms)
            verdict = "PASS" if b.median <= CRITERION_MS else "FAIL"
            rows.append(
                f"| {template} | {slider} | {b.fmt(unit=' ms')} | {max(browser_ms):.0f} ms | "
                f"{h.fmt(unit=' ms')} | {verdict} |"
            )
        page.close()
    finally:
        proc.terminate()
        proc.wait(timeout=30)
    return rows


def main(argv: list[str] | None = None) -> int:
    from playwright.sync_api import sync_playwright

    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--moves", type=int, default=40, help="timed moves per slider")
    ap.add_argument("--only", nargs="*", default=None, help="template names")
    args = ap.parse_args(argv)
    header = [
        f"slider-to-drawn update in Chromium, {args.moves} moves per slider; "
        f"criterion: median <= {CRITERION_MS:.0f} ms",
        "",
        "| template | slider | page update median [q1, q3] | worst | HTTP state alone "
        "median [q1, q3] | median <= 300 ms |",
        "|---|---|---|---|---|---|",
    ]
    print("\n".join(header), flush=True)
    with sync_playwright() as pw:
        browser = pw.chromium.launch(executable_path="/usr/bin/chromium", args=CHROMIUM_ARGS)
        try:
            for template in args.only or TEMPLATES:
                for row in bench_template(browser, template, args.moves):
                    print(row, flush=True)
        finally:
            browser.close()
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
