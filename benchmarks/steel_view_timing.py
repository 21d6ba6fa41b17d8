"""The explorer's Steel view beside today's Simulate press, in one run
(``bench_explore.py --steel ROUNDS``).

On one page of the default template in Chromium, round by round in rotated
order (the same load for each), with alpha moved by 1 to 3 degrees from the design
shown every time (up, and down past 40 degrees):

* **Simulate press**: the value typed (its state drawn first), then a click of
  Simulate, to the frame that shows the steel (``explore:simulated``; J2
  through the thickness since 7 December, the moment law before; the Steel
  view's is the moment law);
* **Steel view release**: the Steel view on, alpha's slider moved and released
  (``input``, ``change``) to the frame that shows the new design's steel
  (``explore:steel``; the state's update comes first, then the simulation);
  the form comes first, then (**its verdict**) the "stands" of its reserve
  check (``explore:steel-checked``; ``/api/steel/check``), timed from the
  same release;
* **second release**: two releases 0.5 s apart (the first design's simulation
  running when the second comes, 1 degree apart), from the second release to
  its steel shown: the stale run is given up at its next Newton step, not
  finished.

Each row gives, per press or release, the time to the frame shown, the
server's ``server_ms`` (the request's time on the server, including waiting
for a run it supersedes) and ``cpu_ms`` (the simulation's CPU time, whatever
else the shared machine runs); the target is the release's new standing
form within 1 s of server time.
"""

from __future__ import annotations

import os

from docs_block import machine_line, write_block
from interleave import stats_of

__all__ = ["STEEL_HEADER", "bench_steel", "steel_rows", "write_steel_docs"]

#: Seconds between the two releases of the "second release" row.
GAP_S = 0.5

STEEL_HEADER = [
    "| action | to the steel shown: median [q1, q3] | server_ms: median [q1, q3] | "
    "cpu_ms: median [q1, q3] | server <= 1 s |",
    "|---|---|---|---|---|",
]

# In the page: do `action` ('simulate', 'release' or 'twice') at alpha `value`
# (and `second`), resolve with the event's detail and the time (ms from the
# last release or the click) to the frame shown, after its paint and the GPU.
ACT = """async ([action, value, second, gap]) => {
  const gl = document.getElementById('view').getContext('webgl2');
  const px = new Uint8Array(4);
  const event = action === 'simulate' ? 'explore:simulated' : 'explore:steel';
  const slider = document.getElementById('alpha');
  const release = (v) => {
    slider.value = v;
    slider.dispatchEvent(new Event('input', { bubbles: true }));
    slider.dispatchEvent(new Event('change', { bubbles: true }));
  };
  let t0 = performance.now();
  const next = (name) => new Promise((resolve) => {
    const timer = setTimeout(() => resolve(null), 180000);
    window.addEventListener(name, (e) => {
      clearTimeout(timer);
      setTimeout(() => {
        gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, px);
        resolve({ detail: e.detail, shown: performance.now() - t0 });
      }, 0);
    }, { once: true });
  });
  const done = next(event).then(async (r) => {
    if (r === null || !r.detail.checking) return r;
    const c = await next('explore:steel-checked'); // its verdict, from the same release
    return { ...r, checked: c };
  });
  if (action === 'simulate') {
    document.getElementById('simulate').click();
  } else {
    release(value);
    if (action === 'twice') {
      await new Promise((r) => setTimeout(r, gap));
      t0 = performance.now();
      release(second);
    }
  }
  return await done;
}"""


def _typed(page, value: str) -> None:
    """Type alpha = ``value`` in its number box and wait for its state drawn."""
    n = int(page.locator("body").get_attribute("data-updates") or 0)
    page.locator("#alpha-num").fill(value)
    page.locator(f"body[data-updates='{n + 1}']").wait_for(state="attached", timeout=60_000)


def _steel(page, on: bool) -> None:
    """Switch the Steel view on or off (waiting for the current design's steel when on)."""
    toggle = page.locator("#steel")
    if (toggle.get_attribute("aria-pressed") == "true") != on:
        n = int(page.locator("body").get_attribute("data-steel") or 0)
        toggle.click()
        if on:
            page.locator(f"body[data-steel='{n + 1}']").wait_for(state="attached", timeout=180_000)


def _cell(xs: list[float]) -> str:
    return stats_of(xs).fmt(scale=1e-3, unit=" s") if xs else "–"


def steel_rows(page, rounds: int) -> list[str]:
    """The table's rows (:data:`STEEL_HEADER`) from ``rounds`` rounds on ``page``
    (the explorer of patkau-one-fold, loaded): each action once a round, in
    rotated order, each at alpha values of its own (30.5, 31, ... degrees)."""
    actions = ["simulate", "release", "twice"]
    got: dict[str, list[dict]] = {a: [] for a in actions}
    shown, k = 30.0, 0  # the alpha of the steel (or state) shown
    for i in range(rounds):
        for action in actions[i % 3 :] + actions[: i % 3]:
            step = 1 + k % 3
            k += 1
            value = shown + step if shown + step <= 40 else shown - step
            first, second = f"{value:g}", f"{value + 1:g}"
            shown = value + 1 if action == "twice" else value
            if action == "simulate":
                _steel(page, False)
                _typed(page, first)
            else:
                _steel(page, True)
            r = page.evaluate(ACT, [action, first, second, 1e3 * GAP_S])
            if r is None or not r["detail"]["ok"]:
                raise SystemExit(f"{action} at alpha {first}: no steel shown ({r})")
            got[action].append(r)
    names = {
        "simulate": "Simulate press (today)",
        "release": "Steel view: a slider's release",
        "twice": f"Steel view: a second release {GAP_S:g} s after the first",
    }
    rows = []
    for action in actions:
        rows.append(_row(names[action], got[action]))
        checked = [r["checked"] for r in got[action] if r.get("checked")]
        if action == "release" and checked:
            rows.append(_row(f"{names[action]}: its verdict (reserve check)", checked, "–"))
    return rows


def _row(name: str, rs: list[dict], verdict: str | None = None) -> str:
    """A table row: to the frame shown, the request's server_ms and cpu_ms."""
    server = [r["detail"]["server_ms"] for r in rs]
    passed = verdict or ("PASS" if stats_of(server).median <= 1000 else "FAIL")
    return (
        f"| {name} | {_cell([r['shown'] for r in rs])} | {_cell(server)} | "
        f"{_cell([r['detail']['cpu_ms'] for r in rs])} | {passed} |"
    )


def bench_steel(browser, rounds: int, start_server) -> list[str]:
    """:func:`steel_rows` on a server of its own (``start_server(template)``:
    bench_explore's, the process and its port) and a page of patkau-one-fold."""
    proc, port = start_server("patkau-one-fold")
    try:
        page = browser.new_page(viewport={"width": 1400, "height": 860})
        page.goto(f"http://127.0.0.1:{port}/")
        page.locator("body[data-updates='1']").wait_for(state="attached", timeout=60_000)
        return steel_rows(page, rounds)
    finally:
        proc.terminate()
        proc.wait(timeout=30)


def write_steel_docs(rows: list[str], rounds: int, load0: float) -> None:
    """Paste the table into docs/benchmarks.md's ``bench_explore_steel`` block."""
    load = f"Load average (1 min) {load0:.1f} at the start, {os.getloadavg()[0]:.1f} at the end."
    body = "\n".join(
        [
            f"patkau-one-fold, coarse mesh, {rounds} rounds, the actions of a round in rotated "
            "order:",
            "",
            *STEEL_HEADER,
            *rows,
            "",
            machine_line() + " " + load,
        ]
    )
    command = f"python benchmarks/bench_explore.py --only --steel {rounds} --write-docs"
    write_block("bench_explore_steel", body, command)
