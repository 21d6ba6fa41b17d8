"""How close any fold of the family comes to the design: a grid of alpha and
beta simulated as ``onefold compensate`` simulates a candidate, and each
standing steel measured against the template's own design.

``onefold compensate`` stops where its least squares stops; this scan asks
the family itself: over a grid of folds (alpha, beta; h_c as the template
has it), the standing steel's largest and rms distance from the design,
each simulated by :func:`onefold_cad.compensate.evaluate.simulate_standing`
(``onefold simulate`` on the given mesh) and measured by
:func:`onefold_cad.compensate.evaluate.standing_measures` (the distance the
command reports). The smallest largest distance on the grid against a fifth
of the uncompensated one (the template's own fold, measured the same way)
says whether compensating within the family could reach that fifth on this
mesh. Prints the grid and a markdown summary (docs/compensate.md's block
``compensate-family``; ``--write-docs`` pastes it). Run from the repository
root::

    .venv/bin/python benchmarks/compensate_family.py [TEMPLATE] [--alpha 30:40:2]
        [--beta 26:36:2] [--mesh coarse] [-j 2] [--write-docs]
"""

from __future__ import annotations

import argparse
import itertools
import sys
import time
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

import numpy as np

from onefold_cad.compensate.evaluate import node_weights, simulate_standing, standing_measures
from onefold_cad.templates import find_template, load_template

ROOT = Path(__file__).resolve().parents[1]
DOC = ROOT / "docs" / "compensate.md"
BLOCK = "compensate-family"

Row = tuple[float, float, float | None, float | None, float]


def grid(text: str) -> list[float]:
    """``START:STOP:STEP`` (STOP included) or ``A,B,C`` as a list of degrees."""
    if ":" in text:
        a, b, s = (float(v) for v in text.split(":"))
        return [float(v) for v in np.arange(a, b + s / 2, s)]
    return [float(v) for v in text.split(",")]


def one(args: tuple[str, str, float, float]) -> Row:
    """Simulate the template folded to (alpha, beta) and measure it against
    the template's design: (alpha, beta, max, rms or None, CPU s)."""
    name, mesh, alpha, beta = args
    design = load_template(find_template(name))
    fold = design.with_changes(frame=design.frame.with_changes(alpha=alpha, beta=beta))
    s = simulate_standing(fold, mesh)
    if not s.stands or s.positions is None:
        return alpha, beta, None, None, s.cpu_s
    m = standing_measures(design, s.flat, node_weights(s.flat, s.faces), s)
    return alpha, beta, m.max_deviation, m.rms_deviation, s.cpu_s


def summary(name: str, mesh: str, unit: str, start: Row, rows: list[Row]) -> str:
    """The markdown table of the scan's result."""
    standing = [r for r in rows if r[2] is not None]
    if start[2] is None or not standing:
        return f"{name} ({mesh} mesh): the template's own fold or every fold scanned falls."
    best = min(standing, key=lambda r: r[2])  # type: ignore[arg-type,return-value]
    best_rms = min(standing, key=lambda r: r[3])  # type: ignore[arg-type,return-value]
    alphas = sorted({r[0] for r in rows})
    betas = sorted({r[1] for r in rows})
    fifth = start[2] / 5
    return "\n".join(
        [
            "| template, mesh | grid (deg) | folds standing | uncompensated max / rms | a fifth "
            "of it | smallest max on the grid (alpha, beta) | smallest rms (alpha, beta) | "
            "CPU |",
            "|---|---|---|---|---|---|---|---|",
            f"| {name}, {mesh} | alpha {alphas[0]:g}..{alphas[-1]:g}, beta {betas[0]:g}.."
            f"{betas[-1]:g} ({len(rows)}) | {len(standing)} | {start[2]:.4g} / {start[3]:.4g} "
            f"{unit} | {fifth:.4g} {unit} | {best[2]:.4g} {unit} ({best[0]:g}, {best[1]:g}) | "
            f"{best_rms[3]:.4g} {unit} ({best_rms[0]:g}, {best_rms[1]:g}) | "
            f"{sum(r[4] for r in rows) + start[4]:.0f} s |",
        ]
    )


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("template", nargs="?", default="patkau-one-fold")
    ap.add_argument("--alpha", default="30:40:2", help="START:STOP:STEP or A,B,.. (deg)")
    ap.add_argument("--beta", default="26:36:2", help="START:STOP:STEP or A,B,.. (deg)")
    ap.add_argument("--mesh", default="coarse", choices=("coarse", "normal"))
    ap.add_argument("-j", "--jobs", type=int, default=2)
    ap.add_argument("--write-docs", action="store_true")
    ns = ap.parse_args()
    design = load_template(find_template(ns.template))
    f = design.frame
    tasks = [
        (ns.template, ns.mesh, a, b) for a, b in itertools.product(grid(ns.alpha), grid(ns.beta))
    ]
    t0 = time.monotonic()
    with ProcessPoolExecutor(ns.jobs) as ex:
        start = ex.submit(one, (ns.template, ns.mesh, f.alpha, f.beta))
        rows = list(ex.map(one, tasks))
    for a, b, mx, rms, cpu in rows:
        got = "falls" if mx is None else f"max {mx:8.4g}  rms {rms:8.4g}"
        print(f"alpha {a:5.1f}  beta {b:5.1f}  {got}  ({cpu:.1f} s CPU)")
    text = summary(ns.template, ns.mesh, design.units.value, start.result(), rows)
    print(f"\n{text}\n\nwall {time.monotonic() - t0:.0f} s")
    if ns.write_docs:
        from docs_block import machine_line, write_block  # type: ignore[import-not-found]

        command = (
            f".venv/bin/python benchmarks/compensate_family.py {ns.template} --alpha {ns.alpha} "
            f"--beta {ns.beta} --mesh {ns.mesh} --write-docs"
        )
        write_block(BLOCK, f"{text}\n\n{machine_line()}", command, path=DOC)


if __name__ == "__main__":
    sys.path.insert(0, str(Path(__file__).resolve().parent))
    main()
