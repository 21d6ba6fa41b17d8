#!/usr/bin/env python3
"""Fold our FOLD files in Origami Simulator (the web app) and measure how close it gets.

A manual check, not part of the test suite: it needs a checkout of Origami
Simulator (MIT licence, https://github.com/amandaghassaei/OrigamiSimulator;
not vendored here), Debian's chromium (/usr/bin/chromium) and playwright::

    git clone https://github.com/amandaghassaei/OrigamiSimulator /tmp/origami-sim
    .venv/bin/python scripts/origami_simulator_check.py /tmp/origami-sim
    .venv/bin/python scripts/origami_simulator_check.py /tmp/origami-sim --write-docs

It serves the checkout on 127.0.0.1 (http.server in a thread), opens it in
headless chromium with software WebGL (SwiftShader), and for each design
(every template by default, or the names / .fold files given) loads the
FOLD file through the app's own file input (``#fileSelector``), sets the
fold to 100 % (``globals.creasePercent = 1``), pauses the app's animation
loop and runs its dynamic solver (``globals.model.step``) in chunks until
no vertex moves more than ``--settle`` (a fraction of the sheet's size) in
a chunk, or ``--max-steps``. Then it reads the app's vertex positions
(``globals.model.getPositionsArray()``, divided by ``globals.scale``) and
its strain (the "average vertex strain" it shows, ``#globalError``), and
reports per design:

* ``nan``: whether any position is not finite (or beyond 1000 sheet sizes:
  the solver blew up);
* ``dist``: the largest distance of a vertex from our ``foldedForm`` after
  the best rotation and translation (Kabsch, proper rotations only), and
  ``rms`` the root mean square, both as fractions of the sheet's size
  (``onefold:sheet_size``, the largest distance from H to the outline);
* ``wrong``: the creases (M/V edges) whose dihedral angle in the app has the
  opposite sign to ``edges_foldAngle`` (folded the wrong way; angles under
  0.01 deg count as unfolded, not wrong) and ``err`` the largest difference
  between the app's dihedral and ``edges_foldAngle`` (deg);
* ``strain``: the app's average vertex strain (%), and the steps run;
* ``load``: the file's busiest vertex for the app's time step
  (:func:`vertex_load`; over about 15 the app's solver diverges).

``--write-docs`` puts the table into docs/formats.md between the markers
``<!-- origami-simulator:begin -->`` and ``<!-- origami-simulator:end -->``.
``--screenshots DIR`` saves the app's view of each folded design.

Exit status: 0 when every design folds without NaN, within ``--target``
(3 % by default) of the sheet's size and with no crease the wrong way; 1
otherwise; 2 for bad arguments (no checkout, no chromium).
"""

from __future__ import annotations

import argparse
import functools
import http.server
import json
import math
import sys
import tempfile
import threading
from dataclasses import dataclass
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

sys.path.insert(0, str(ROOT / "benchmarks"))
from chromium import CHROMIUM  # noqa: E402
from chromium import CHROMIUM_ARGS as _ARGS  # noqa: E402

#: As the explorer's tests start it, plus SwiftShader allowed for WebGL 1 contexts.
CHROMIUM_ARGS = [*_ARGS, "--enable-unsafe-swiftshader"]
DOCS = ROOT / "docs" / "formats.md"
BEGIN, END = "<!-- origami-simulator:begin -->", "<!-- origami-simulator:end -->"
#: Positions this many sheet sizes from the origin count as NaN (the solver blew up).
BLOWN_UP = 1e3
#: An angle under this (deg) counts as unfolded, not as folded the wrong way.
UNFOLDED_DEG = 0.01


@dataclass(frozen=True)
class Result:
    """One design folded in the app (lengths as fractions of the sheet's size)."""

    name: str
    vertices: int
    faces: int
    nan: bool
    dist: float
    rms: float
    wrong: int
    creases: int
    err_deg: float
    strain_pct: float
    steps: int
    settled: bool
    load: float

    def ok(self, target: float) -> bool:
        return not self.nan and self.dist <= target and self.wrong == 0


class _Quiet(http.server.SimpleHTTPRequestHandler):
    def log_message(self, format: str, *args: object) -> None:  # noqa: A002
        pass


def serve(checkout: Path) -> http.server.ThreadingHTTPServer:
    """The checkout served on a free port of 127.0.0.1 (in a daemon thread)."""
    handler = functools.partial(_Quiet, directory=str(checkout))
    srv = http.server.ThreadingHTTPServer(("127.0.0.1", 0), handler)
    threading.Thread(target=srv.serve_forever, daemon=True).start()
    return srv


def fold_files(names: list[str], out: Path) -> list[Path]:
    """FOLD files: a .fold path as it is, a template name written to ``out``."""
    from onefold_cad import fold_design
    from onefold_cad.export.fold.file import write_fold
    from onefold_cad.templates import load_template

    paths = []
    for name in names:
        if name.endswith(".fold"):
            paths.append(Path(name))
            continue
        design = load_template(name)
        paths.append(write_fold(design, fold_design(design), out / f"{design.name}.fold"))
    return paths


def kabsch(p: np.ndarray, q: np.ndarray) -> np.ndarray:
    """``p`` moved by the proper rigid motion that best fits it onto ``q`` (least squares)."""
    pc, qc = p.mean(axis=0), q.mean(axis=0)
    u, _, vt = np.linalg.svd((p - pc).T @ (q - qc))
    d = np.sign(np.linalg.det(u @ vt))
    return (p - pc) @ (u @ np.diag([1.0, 1.0, d]) @ vt) + qc


def vertex_load(points: np.ndarray, edges: np.ndarray) -> float:
    """The largest, over the vertices, of sum over a vertex's edges of
    sqrt(shortest edge / edge): the app sizes its explicit time step for its
    stiffest (shortest) edge, a vertex of many edges is stiffer (its damping
    term's explicit update is stable below about 15 at the app's damping
    ratio 0.45; see docs/formats.md)."""
    length = np.linalg.norm(points[edges[:, 1]] - points[edges[:, 0]], axis=1)
    share = np.sqrt(length.min() / length)
    total = np.zeros(len(points))
    np.add.at(total, edges[:, 0], share)
    np.add.at(total, edges[:, 1], share)
    return float(total.max())


def signed_dihedrals(points: np.ndarray, faces: list[list[int]], edges: np.ndarray) -> np.ndarray:
    """Per edge, the signed angle (deg) between its two faces' normals over
    ``points`` (valley positive: the left face's normal points towards the
    right face's far vertex, the FOLD spec's sense); 0 on the boundary."""
    half: dict[tuple[int, int], int] = {}
    for f in faces:
        for i in range(len(f)):
            half[(f[i], f[(i + 1) % len(f)])] = f[(i + 2) % len(f)]
    out = np.zeros(len(edges))
    for i, (a, b) in enumerate(edges.tolist()):
        if (a, b) not in half or (b, a) not in half:
            continue
        c, d = half[(a, b)], half[(b, a)]
        ab = points[b] - points[a]
        n1 = np.cross(ab, points[c] - points[a])
        n2 = np.cross(-ab, points[d] - points[b])
        n1 /= np.linalg.norm(n1)
        n2 /= np.linalg.norm(n2)
        angle = math.degrees(math.atan2(np.linalg.norm(np.cross(n1, n2)), float(n1 @ n2)))
        out[i] = angle if n1 @ (points[d] - points[a]) > 0.0 else -angle
    return out


_LOADED = """n => globals.model && globals.model.getNodes().length === n && !globals.needsSync
    && !globals.simNeedsSync"""
_SETUP = """p => {
    globals.simulationRunning = false;
    globals.axialStiffness = p.axial; globals.faceStiffness = p.face;
    globals.creaseStiffness = p.crease; globals.panelStiffness = p.panel;
    globals.percentDamping = p.damping;
    globals.materialHasChanged = true; globals.creaseMaterialHasChanged = true;
    globals.setCreasePercent(p.percent); globals.shouldChangeCreasePercent = true;
}"""
_PERCENT = """p => { globals.setCreasePercent(p); globals.shouldChangeCreasePercent = true; }"""
_STEP = """n => { globals.model.step(n);
    return Array.from(globals.model.getPositionsArray()); }"""
_READ = """() => ({scale: globals.scale, strain: document.querySelector('#globalError').textContent,
    creases: globals.model.getCreases().length})"""


def check(page, base: str, path: Path, args: argparse.Namespace) -> Result:
    """Load ``path`` through the app's file input, fold it, measure it."""
    doc = json.loads(path.read_text(encoding="utf-8"))
    ours = np.array(doc["file_frames"][0]["vertices_coords"], dtype=float)
    size = float(doc.get("onefold:sheet_size") or np.ptp(ours, axis=0).max())
    edges = np.array(doc["edges_vertices"], dtype=int)
    target = np.array(doc["edges_foldAngle"], dtype=float)
    fold = np.isin(doc["edges_assignment"], ["M", "V"])
    page.goto(base + "/index.html")
    page.wait_for_function("() => window.globals && globals.model && globals.pattern")
    page.set_input_files("#fileSelector", str(path))
    page.wait_for_function(_LOADED, arg=len(ours), timeout=120_000)
    page.evaluate(_SETUP, {"axial": args.axial, "face": args.face, "crease": args.crease,
                           "panel": args.panel, "damping": args.damping,
                           "percent": 1.0 if args.ramp <= 0 else 0.0})  # fmt: skip
    scale = page.evaluate(_READ)["scale"]
    prev = np.array(page.evaluate(_STEP, 1), dtype=float).reshape(-1, 3) / scale
    steps, settled = 1, False
    while steps < args.max_steps:
        if steps < args.ramp:  # fold percent rising from 0 to 1 over the first RAMP steps
            page.evaluate(_PERCENT, min(1.0, (steps + args.chunk) / args.ramp))
        pos = np.array(page.evaluate(_STEP, args.chunk), dtype=float).reshape(-1, 3) / scale
        steps += args.chunk
        if not np.all(np.isfinite(pos)) or np.abs(pos).max() > BLOWN_UP * size:
            prev = pos
            break
        # the change of shape (the app's model may also drift and turn as a whole)
        moved = float(np.max(np.linalg.norm(kabsch(pos, prev) - prev, axis=1))) / size
        prev = pos
        if args.verbose:
            gap = float(np.max(np.linalg.norm(kabsch(pos, ours) - ours, axis=1))) / size
            print(f"  {path.stem} steps {steps}: moved {moved:.2e}, distance {gap:.4f}", flush=True)
        if moved <= args.settle and steps >= args.ramp:
            settled = True
            break
    info = page.evaluate(_READ)
    if args.screenshots:  # centred first: the app's model drifts off the camera as a whole
        page.evaluate("() => { globals.shouldCenterGeo = true; globals.model.step(1); }")
        page.wait_for_timeout(500)
        args.screenshots.mkdir(parents=True, exist_ok=True)
        page.screenshot(path=str(args.screenshots / f"{path.stem}.png"))
    nan = not np.all(np.isfinite(prev)) or np.abs(prev).max() > BLOWN_UP * size
    if nan:
        dist = rms = err = math.nan
        wrong = int(fold.sum())
    else:
        fitted = kabsch(prev, ours)
        gap = np.linalg.norm(fitted - ours, axis=1) / size
        dist, rms = float(gap.max()), float(np.sqrt(np.mean(gap**2)))
        app = signed_dihedrals(prev, doc["faces_vertices"], edges)
        flipped = (np.sign(app) == -np.sign(target)) & (np.abs(app) > UNFOLDED_DEG)
        wrong = int(np.sum(flipped & fold))
        err = float(np.max(np.abs(app - target)[fold]))
    strain = float(info["strain"].split()[0]) if info["strain"].strip() else math.nan
    if nan:
        strain = math.nan
    load = vertex_load(np.array(doc["vertices_coords"], dtype=float), edges)
    return Result(path.stem, len(ours), len(doc["faces_vertices"]), nan, dist, rms, wrong,
                  int(fold.sum()), err, strain, steps, settled, load)  # fmt: skip


def table(results: list[Result], command: str) -> str:
    """The results as a markdown table with the command that made it."""
    rows = [
        f"Made by `{command}` (Origami Simulator's dynamic solver, fold 100 %).",
        "",
        "| design | vertices | faces | NaN | max distance | RMS distance | creases the wrong way "
        "| largest crease error (deg) | app strain (%) | steps | settled | vertex load |",
        "|---|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    for r in results:
        rows.append(
            f"| {r.name} | {r.vertices} | {r.faces} | {'yes' if r.nan else 'no'} "
            f"| {100 * r.dist:.2f} % | {100 * r.rms:.2f} % | {r.wrong} of {r.creases} "
            f"| {r.err_deg:.2f} | {r.strain_pct:.4f} | {r.steps} | {'yes' if r.settled else 'no'} "
            f"| {r.load:.1f} |"
        )
    return "\n".join(rows)


def _command(argv: list[str]) -> str:
    """The command line that made the table, the checkout's path as CHECKOUT
    and without --screenshots."""
    words, skip = [], False
    for i, word in enumerate(argv):
        if skip:
            skip = False
        elif word == "--screenshots":
            skip = True
        elif not word.startswith("--screenshots=") and i == 0:
            words.append("CHECKOUT")
        elif not word.startswith("--screenshots="):
            words.append(word)
    return " ".join([".venv/bin/python scripts/origami_simulator_check.py", *words])


def write_docs(text: str) -> None:
    doc = DOCS.read_text(encoding="utf-8")
    a, b = doc.index(BEGIN) + len(BEGIN), doc.index(END)
    DOCS.write_text(doc[:a] + "\n" + text + "\n" + doc[b:], encoding="utf-8")


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("checkout", type=Path, help="a checkout of Origami Simulator (its index.html)")
    ap.add_argument("designs", nargs="*", help="template names or .fold files (default: all)")
    ap.add_argument("--max-steps", type=int, default=200_000)
    ap.add_argument("--chunk", type=int, default=2000, help="solver steps between checks")
    ap.add_argument(
        "--settle",
        type=float,
        default=1e-5,
        help="settled when no vertex moves more than this x size in a chunk",
    )
    ap.add_argument("--target", type=float, default=0.03, help="largest distance allowed")
    ap.add_argument("--axial", type=float, default=20.0, help="axial stiffness (app: 20)")
    ap.add_argument("--face", type=float, default=0.2, help="face stiffness (app: 0.2)")
    ap.add_argument("--crease", type=float, default=0.7, help="crease stiffness (app: 0.7)")
    ap.add_argument("--panel", type=float, default=0.7, help="panel stiffness (app: 0.7)")
    ap.add_argument("--damping", type=float, default=0.45, help="damping ratio (app: 0.45)")
    ap.add_argument("--screenshots", type=Path, help="save the app's view of each design here")
    ap.add_argument(
        "--ramp",
        type=int,
        default=0,
        help="raise the fold from 0 to 100 %% over this many steps (0: at once)",
    )
    ap.add_argument("--verbose", action="store_true", help="print each chunk's numbers")
    ap.add_argument("--write-docs", action="store_true", help="put the table in docs/formats.md")
    args = ap.parse_args(argv)  # fmt: skip
    if not (args.checkout / "index.html").is_file():
        print(f"checkout: no index.html in {args.checkout}", file=sys.stderr)
        return 2
    if not Path(CHROMIUM).exists():
        print(f"chromium: {CHROMIUM} not found (apt-get install chromium)", file=sys.stderr)
        return 2
    from playwright.sync_api import sync_playwright

    from onefold_cad.templates import list_templates

    names = args.designs or [t.name for t in list_templates()]
    srv = serve(args.checkout)
    base = f"http://127.0.0.1:{srv.server_address[1]}"
    results = []
    with tempfile.TemporaryDirectory() as tmp, sync_playwright() as pw:
        paths = fold_files(names, Path(tmp))
        browser = pw.chromium.launch(executable_path=CHROMIUM, args=CHROMIUM_ARGS)
        page = browser.new_page(viewport={"width": 1000, "height": 800})
        page.route("**/*", lambda r: r.continue_() if r.request.url.startswith(base) else r.abort())
        for path in paths:
            r = check(page, base, path, args)
            results.append(r)
            print(
                f"{r.name:<18} V={r.vertices:<6} nan={r.nan!s:<5} dist={100 * r.dist:6.2f} % "
                f"rms={100 * r.rms:6.2f} % wrong={r.wrong}/{r.creases} err={r.err_deg:7.2f} deg "
                f"strain={r.strain_pct:.4f} % steps={r.steps} settled={r.settled} "
                f"load={r.load:.1f}",
                flush=True,
            )
        browser.close()
    srv.shutdown()
    if args.write_docs:
        write_docs(table(results, _command(argv if argv is not None else sys.argv[1:])))
    return 0 if all(r.ok(args.target) for r in results) else 1


if __name__ == "__main__":
    sys.exit(main())
