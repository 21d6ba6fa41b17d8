"""How fast the explorer's page follows a slider, in a real browser on this machine.

Starts ``onefold explore TEMPLATE --no-browser --port 0`` (its own process),
opens the page in Debian's Chromium (playwright, software WebGL: SwiftShader)
and drags a slider as a user would: sets its value and fires ``input``, four times
(a drag), then ``change`` (the release), then types a value in the slider's
number box (``input``: not a drag). Each is timed inside the page, from its
event to the frame that shows it:

* **drag frame**: a slider's ``input`` to the frame that shows the new state
  while the drag goes on. On a GPU too slow for full frames (software GL here)
  the page draws these at half the pixel ratio (quality.js); the criterion of
  issue 24 (median <= 50 ms) is judged on this one: it is what a user waits
  for, move after move, while dragging;
* **settled**: the release (``change``) to the full-quality frame of the same
  state (no server: the page redraws what it has);
* **full update**: the number box's ``input`` to the full-quality frame of the
  new state (a baseline without drag frames draws every update so).

"The frame that shows" is the page's first animation frame after the frame
was drawn (its ``explore:updated`` or ``explore:settled`` event), then that
frame's style, layout and paint (a task queued from the frame runs after
them) and the GPU's drawing of the 3D view (a one-pixel ``readPixels`` of the
canvas returns only when the WebGL commands before it are done: software GL
draws on the CPU, after the page's script has handed it the frame).

The page's performance marks (``explore:request`` .. ``explore:drawn``) and
the ``server_ms`` of its state give each update's breakdown: the server
computing the state, the rest of the HTTP round trip, reading the JSON,
setting numbers, messages and the 3D form, the flat pattern and the render
call, waiting for the frame, then paint and the GPU. Interleaved with each
round, in alternating order, the same state is fetched over HTTP from Python
(no browser). With ``--baseline COMMIT`` the explorer of that commit runs
beside this tree's, round by round in alternating order, and the paired
ratios (this tree / baseline, round by round) are printed. Prints medians with
their spread (25th and 75th percentile); asserts nothing; ``--write-docs``
pastes the tables into docs/benchmarks.md. ``--steel ROUNDS`` adds the Steel
view's slider release beside today's Simulate press, measured in the same run
(:mod:`steel_view_timing`; ``--only`` with no name: that table alone).

Run from the repository root::

    .venv/bin/python benchmarks/bench_explore.py [--moves 40] [--only NAME ...]
        [--baseline COMMIT] [--steel ROUNDS] [--write-docs]
"""

from __future__ import annotations

import argparse
import http.client
import io
import math
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from urllib.parse import urlencode

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

from chromium import CHROMIUM, CHROMIUM_ARGS  # noqa: E402
from docs_block import ROOT, machine_line, write_block  # noqa: E402
from git_baseline import extract  # noqa: E402
from interleave import stats_of  # noqa: E402
from steel_view_timing import STEEL_HEADER, bench_steel, write_steel_docs  # noqa: E402

TEMPLATES = ["patkau-one-fold", "table1-row4", "star-polygon"]
#: Issue 24: the default template's page update in at most 50 ms (median of the
#: drag frames: what a user waits for while dragging a slider).
CRITERION_MS = 50.0
#: Slider inputs per drag (then its change event, then one typed value).
DRAG = 4
#: The page's performance marks of one update, in order (explore.js).
MARKS = ["explore:request", "explore:answer", "explore:parsed", "explore:form", "explore:drawn"]
#: The breakdown's parts: name -> (from, to), times as in :data:`MOVE`'s answer.
PARTS = {
    "server": None,  # the state's own server_ms
    "HTTP rest": ("explore:request", "explore:answer"),  # minus server
    "JSON": ("explore:answer", "explore:parsed"),
    "numbers + 3D form": ("explore:parsed", "explore:form"),
    "flat + render call": ("explore:form", "explore:drawn"),
    "to the frame": ("explore:drawn", "raf"),
    "paint + GPU": ("raf", "shown"),
}

# In the page: resolve `event`'s next occurrence with the times (ms from t0) of
# its animation frame (raf) and of the frame shown (after that frame's paint and
# the GPU's drawing of the canvas); null after `wait` ms without it.
SHOWN = """(event, t0, wait) => {
  const gl = document.getElementById('view').getContext('webgl2');
  const px = new Uint8Array(4);
  return new Promise((resolve) => {
    const timer = setTimeout(() => resolve(null), wait);
    window.addEventListener(event, (e) => {
      clearTimeout(timer);
      const raf = performance.now();
      setTimeout(() => {  // after the frame's style, layout and paint
        gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, px);  // the GPU's drawing done
        resolve({ detail: e.detail, raf: raf - t0, shown: performance.now() - t0 });
      }, 0);
    }, { once: true });
  });
}"""

# In the page: set slider `id` (or its number box, `box`) to `value` and fire
# `input`; resolve with the times (ms from the input event) of the update's
# marks, its first animation frame (raf), the frame shown, and its quality.
MOVE = (
    """async ([id, value, box]) => {
  const shown = """
    + SHOWN
    + """;
  const el = document.getElementById(box ? `${id}-num` : id);
  const t0 = performance.now();
  const done = shown('explore:updated', t0, 60000);
  el.value = value;
  el.dispatchEvent(new Event('input', { bubbles: true }));
  const r = await done;
  const out = { ok: r.detail.ok, server: r.detail.server_ms, raf: r.raf, shown: r.shown,
    quality: r.detail.quality ?? null };
  for (const m of performance.getEntriesByType('mark')) {
    if (m.name.startsWith('explore:') && m.startTime >= t0) out[m.name] = m.startTime - t0;
  }
  return out;
}"""
)

# In the page: release slider `id` (its change event); resolve with the times of
# the full-quality frame it draws (explore:settled), or null when none comes.
RELEASE = (
    """async (id) => {
  const shown = """
    + SHOWN
    + """;
  const t0 = performance.now();
  const done = shown('explore:settled', t0, 1500);
  document.getElementById(id).dispatchEvent(new Event('change', { bubbles: true }));
  const r = await done;
  return r && { raf: r.raf, shown: r.shown, quality: r.detail.quality };
}"""
)


def start_server(
    template: str, package_dir: Path | None = None
) -> tuple[subprocess.Popen[str], int]:
    """``onefold explore TEMPLATE --no-browser --port 0`` and the port it printed
    (the package of ``package_dir`` first on the path when given: a baseline)."""
    env = dict(os.environ)
    if package_dir is not None:
        env["PYTHONPATH"] = os.pathsep.join([str(package_dir), env.get("PYTHONPATH", "")])
    proc = subprocess.Popen(
        [
            sys.executable,
            "-c",
            "from onefold_cad.cli.main import main; raise SystemExit(main())",
            "explore",
            template,
            "--no-browser",
            "--port",
            "0",
        ],
        stderr=subprocess.PIPE,
        text=True,
        env=env,
        cwd=package_dir or ROOT,  # python -c puts its folder first on the path
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


def _parts(r: dict[str, float]) -> dict[str, float]:
    """One move's breakdown (ms) from :data:`MOVE`'s answer ``r`` (NaN where a
    baseline's page leaves no mark)."""
    out = {}
    for name, span in PARTS.items():
        if span is None:
            out[name] = r.get("server") if r.get("server") is not None else math.nan
        else:
            out[name] = r.get(span[1], math.nan) - r.get(span[0], math.nan)
    out["HTTP rest"] -= out["server"]
    return out


def _fmt(xs: list[float], unit: str = " ms") -> str:
    return stats_of(xs).fmt(unit=unit) if xs else "–"


def _verdict(xs: list[float]) -> str:
    return "–" if not xs else ("PASS" if stats_of(xs).median <= CRITERION_MS else "FAIL")


def _canvas(page) -> np.ndarray:
    """The 3D view's pixels as the page shows them (a screenshot of the canvas)."""
    from PIL import Image

    return np.asarray(Image.open(io.BytesIO(page.locator("#view").screenshot())).convert("RGB"))


def _round(page, slider: str, vals: list[str]) -> dict[str, list]:
    """One round on ``page``: a drag of :data:`DRAG` inputs, its release, a typed value."""
    drag = [page.evaluate(MOVE, [slider, v, False]) for v in vals[:DRAG]]
    # a release redraws only after a reduced frame (none on a baseline without them)
    release = page.evaluate(RELEASE, slider) if drag[-1]["quality"] == "drag" else None
    full = page.evaluate(MOVE, [slider, vals[DRAG], True])
    for r in [*drag, full]:
        if not r["ok"]:
            raise SystemExit(f"{slider}={vals} gave an error state")
    return {"drag": drag, "settled": [release] if release else [], "full": [full]}


def bench_template(
    browser, template: str, moves: int, versions: list[tuple[str, Path | None]]
) -> tuple[list[str], list[str], list[str]]:
    """The table's rows, the breakdown's rows and the paired ratios' rows of
    ``template``, slider by slider, for each version (label, package folder or
    None for this tree): one server and one page each, their rounds interleaved
    (the order rotated every round)."""
    procs, pages = [], []
    rows, parts_rows, ratio_rows = [], [], []
    per = DRAG + 1  # values per round
    rounds = max(1, moves // DRAG)
    try:
        for _, package in versions:
            proc, port = start_server(template, package)
            procs.append((proc, port))
            page = browser.new_page(viewport={"width": 1400, "height": 860}, bypass_csp=True)
            page.goto(f"http://127.0.0.1:{port}/")
            page.locator("body[data-updates='1']").wait_for(state="attached", timeout=60_000)
            pages.append(page)
        port = procs[0][1]
        for slider in ("alpha", "beta", "hc"):
            vals = values(pages[0], slider, per * (rounds + 1))
            base = {k: pages[0].locator(f"#{k}-num").input_value() for k in ("alpha", "beta", "hc")}
            for page in pages:
                _round(page, slider, vals[:per])  # warm up
            got: list[list[dict[str, list]]] = [[] for _ in pages]
            http_ms: list[float] = []
            steps = [*range(len(pages)), "http"]
            for i in range(rounds):
                vs = vals[per * (i + 1) : per * (i + 2)]
                for step in steps[i % len(steps) :] + steps[: i % len(steps)]:
                    if step == "http":
                        http_ms.append(fetch_state(port, urlencode({**base, slider: vs[0]})))
                    else:
                        got[step].append(_round(pages[step], slider, vs))
            for k, ((label, _), rs) in enumerate(zip(versions, got, strict=True)):
                drag = [r for g in rs for r in g["drag"]]
                full = [r for g in rs for r in g["full"]]
                shown_d = [r["shown"] for r in drag]
                shown_f = [r["shown"] for r in full]
                settled = [r["shown"] for g in rs for r in g["settled"]]
                reduced = sum(r["quality"] == "drag" for r in drag)
                rows.append(
                    f"| {template} | {label} | {slider} | {_fmt(shown_d)} | {max(shown_d):.0f} ms"
                    f" | {reduced}/{len(drag)} | {_fmt(shown_f)} | {_fmt(settled)} | "
                    f"{_fmt(http_ms) if k == 0 else '–'} | {_verdict(shown_d)} | "
                    f"{_verdict(shown_f)} |"
                )
                for what, rs_ in (("drag", drag), ("full", full)):
                    split = [_parts(r) for r in rs_]
                    cells = []
                    for name in PARTS:
                        m = stats_of([p[name] for p in split]).median
                        cells.append("–" if math.isnan(m) else f"{m:.1f}")
                    parts_rows.append(
                        f"| {template} | {label} | {slider} | {what} | " + " | ".join(cells) + " |"
                    )
            shots = [_canvas(page) for page in pages]  # all at the last round's state, full
            for k in range(1, len(versions)):
                changed = 100.0 * float(np.any(shots[0] != shots[k], axis=-1).mean())
                ratios = {}
                for what in ("drag", "full"):
                    ratios[what] = [
                        sum(r["shown"] for r in a[what]) / sum(r["shown"] for r in b[what])
                        for a, b in zip(got[0], got[k], strict=True)
                    ]
                ratio_rows.append(
                    f"| {template} | {slider} | {versions[k][0]} | "
                    f"{_fmt(ratios['drag'], '')} | {_fmt(ratios['full'], '')} | {changed:.2f} % |"
                )
        for page in pages:
            page.close()
    finally:
        for proc, _ in procs:
            proc.terminate()
            proc.wait(timeout=30)
    return rows, parts_rows, ratio_rows


def main(argv: list[str] | None = None) -> int:
    from playwright.sync_api import sync_playwright

    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--moves", type=int, default=40, help="timed drag frames per slider")
    ap.add_argument("--only", nargs="*", default=None, help="template names")
    ap.add_argument(
        "--baseline",
        metavar="COMMIT",
        help="also time the explorer of COMMIT (its package from git), interleaved",
    )
    ap.add_argument(
        "--steel", type=int, default=0, metavar="ROUNDS", help="Steel view and Simulate rounds"
    )
    ap.add_argument("--write-docs", action="store_true", help="update docs/benchmarks.md")
    args = ap.parse_args(argv)
    load0 = os.getloadavg()[0]  # the machine's other work: these times scale with it
    home = tempfile.TemporaryDirectory(prefix="bench_explore_")
    versions: list[tuple[str, Path | None]] = [("this tree", None)]
    if args.baseline:
        versions.append((args.baseline, extract(args.baseline, Path(home.name))))
    rounds = max(1, args.moves // DRAG)
    c = f"{CRITERION_MS:.0f} ms"
    header = [
        f"Slider to shown frame in Chromium (software WebGL), per slider {rounds} drags of "
        f"{DRAG} inputs (the drag frames), their releases (settled) and {rounds} typed values "
        f"(full update); criterion: the drag frame's median <= {c} (what a user waits for "
        "while dragging; the full update's verdict beside it).",
        "",
        "| template | version | slider | drag frame: median [q1, q3] | worst | reduced | "
        "full update: median [q1, q3] | settled: median [q1, q3] | "
        f"HTTP state alone: median [q1, q3] | drag <= {c} | full <= {c} |",
        "|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    templates = TEMPLATES if args.only is None else args.only
    if templates:
        print("\n".join(header), flush=True)
    rows, parts, ratios = [], [], []
    with sync_playwright() as pw:
        browser = pw.chromium.launch(executable_path=CHROMIUM, args=CHROMIUM_ARGS)
        try:
            for template in templates:
                r, p, q = bench_template(browser, template, args.moves, versions)
                rows += r
                parts += p
                ratios += q
                print("\n".join(r), flush=True)
            steel = bench_steel(browser, args.steel, start_server) if args.steel else []
        finally:
            browser.close()
            home.cleanup()
    table2 = [
        "",
        "Where an update's time goes (medians of each part, ms; drag frames and full updates):",
        "",
        "| template | version | slider | frame | " + " | ".join(PARTS) + " |",
        "|---|---|---|---|" + "---|" * len(PARTS),
        *parts,
    ]
    if ratios:
        table2 += [
            "",
            "This tree's time over the baseline's, paired round by round (the same values, "
            "the same load): median [q1, q3] of the ratios; the baseline's drag frames are "
            "full frames. Last column: the share of the canvas's pixels that differ between "
            "this tree's full frame and the baseline's, both at the slider's last state "
            "(the same camera), as the page shows them (screenshots).",
            "",
            "| template | slider | baseline | drag frame / baseline's | "
            "full update / baseline's | full frame's pixels changed |",
            "|---|---|---|---|---|---|",
            *ratios,
        ]
    if rows:
        print("\n".join(table2), flush=True)
    if steel:
        print("\n".join(["", *STEEL_HEADER, *steel]), flush=True)
    if args.write_docs and steel:
        write_steel_docs(steel, args.steel, load0)
    if args.write_docs and rows:
        only = f" --only {' '.join(args.only)}" if args.only else ""
        only += f" --baseline {args.baseline}" if args.baseline else ""
        load = (
            f"Load average (1 min) {load0:.1f} at the start, {os.getloadavg()[0]:.1f} at the end."
        )
        body = "\n".join([*header, *rows, *table2, "", machine_line() + " " + load])
        cmd = f"python benchmarks/bench_explore.py --moves {args.moves}{only} --write-docs"
        write_block("bench_explore", body, cmd)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
