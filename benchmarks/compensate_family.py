"""How close any fold of the family comes to the design: a grid of alpha,
beta and h_c simulated as ``onefold compensate`` simulates a candidate, and each
standing steel measured against the template's own design.

``onefold compensate`` stops where its least squares stops; this scan asks
the family itself: over a grid of folds (alpha, beta and h_c, the last as a
fraction of R cos(alpha) as the command's knob), the standing steel's
largest and rms distance from the design, each simulated by
:func:`onefold_cad.compensate.evaluate.simulate_standing` (``onefold
simulate`` on the given mesh) and measured by
:func:`onefold_cad.compensate.evaluate.standing_measures` (the distance the
command reports). The smallest largest distance on the grid against a fifth
of the uncompensated one (the template's own fold, measured the same way)
says whether compensating within the family could reach that fifth on this
mesh. Prints the grid and a markdown summary (docs/compensate.md's block
``compensate-family``; ``--write-docs`` pastes it). Run from the repository
root::

    .venv/bin/python benchmarks/compensate_family.py [TEMPLATE] [--alpha 30:40:2]
        [--beta 26:36:2] [--hc=0] [--overbend-grid=0] [--mesh coarse]
        [--polish N [--overbend]] [-j 2]
        [--write-docs]

``--overbend-grid`` grids the command's fourth knob too (the crease set
that many deg past the fold; negative: short of it); ``--overbend`` polishes
over it as well (from the grid's best fold's overbend).
"""

from __future__ import annotations

import argparse
import itertools
import math
import sys
import time
from concurrent.futures import ProcessPoolExecutor
from dataclasses import replace
from pathlib import Path

import numpy as np

from onefold_cad.compensate.evaluate import node_weights, simulate_standing, standing_measures
from onefold_cad.templates import find_template, load_template

ROOT = Path(__file__).resolve().parents[1]
DOC = ROOT / "docs" / "compensate.md"
BLOCK = "compensate-family"

#: (alpha, beta, h_c fraction, max or None, rms or None, CPU s, crease overbend deg)
Row = tuple[float, float, float, float | None, float | None, float, float]


def grid(text: str) -> list[float]:
    """``START:STOP:STEP`` (STOP included) or ``A,B,C`` as a list."""
    if ":" in text:
        a, b, s = (float(v) for v in text.split(":"))
        return [float(v) for v in np.arange(a, b + s / 2, s)]
    return [float(v) for v in text.split(",")]


def one(args: tuple[str, str, float, float, float] | tuple[str, str, float, float, float, float],
        overbend: float = 0.0) -> Row:  # fmt: skip
    """Simulate the template folded to (alpha, beta, h_c as a fraction of
    R cos(alpha)), its crease set ``overbend`` deg further, and measure it
    against the template's design: (alpha, beta, h_c fraction, max, rms or
    None, CPU s, overbend); a sixth entry of ``args`` is the overbend."""
    name, mesh, alpha, beta, hc = args[:5]
    if len(args) == 6:
        overbend = float(args[5])  # type: ignore[misc]
    design = load_template(find_template(name))
    half = design.frame.radius * math.cos(math.radians(alpha))
    frame = design.frame.with_changes(alpha=alpha, beta=beta, h_c=hc * half)
    material = replace(design.material, crease_overbend=overbend or None)
    s = simulate_standing(design.with_changes(frame=frame, material=material), mesh)
    if not s.stands or s.positions is None:
        return alpha, beta, hc, None, None, s.cpu_s, overbend
    m = standing_measures(design, s.flat, node_weights(s.flat, s.faces), s)
    return alpha, beta, hc, m.max_deviation, m.rms_deviation, s.cpu_s, overbend


def polish(
    name: str, mesh: str, best: Row, evaluations: int, overbend: bool = False
) -> tuple[Row, float | None]:
    """Nelder-Mead on the largest distance itself (not its least squares) from
    the grid's best fold, ``evaluations`` simulations at most: the family's
    local floor near it (h_c kept inside the command's bounds); with
    ``overbend``, over the crease overbend too (from 0, within the command's
    bounds of +-30 deg). Returns the best row (its CPU the polish's) and its
    overbend (None without)."""
    from scipy.optimize import minimize

    seen: dict[tuple[float, ...], Row] = {}

    def cost(y: np.ndarray) -> float:
        a, b, h = float(y[0]), float(y[1]), float(np.clip(y[2], -0.95, 0.95))
        o = float(np.clip(y[3], -30.0, 30.0)) if overbend else 0.0
        row = seen.setdefault((a, b, h, o), one((name, mesh, a, b, h), o))
        return math.inf if row[3] is None else float(row[3])

    steps = [1.0, 1.0, 0.15] + ([3.0] if overbend else [])
    x0 = np.array(list(best[:3]) + ([best[6]] if overbend else []))
    simplex = np.vstack([x0] + [x0 + np.eye(len(x0))[i] * st for i, st in enumerate(steps)])
    minimize(cost, x0, method="Nelder-Mead",
             options={"maxfev": evaluations, "initial_simplex": simplex})  # fmt: skip
    keys = [k for k, r in seen.items() if r[3] is not None]
    top = min(keys, key=lambda k: seen[k][3])  # type: ignore[arg-type,return-value]
    cpu = sum(r[5] for r in seen.values())
    return (*seen[top][:5], cpu, top[3]), (top[3] if overbend else None)


def summary(
    name: str, mesh: str, unit: str, start: Row, rows: list[Row], polished: Row | None = None,
    polished_overbend: float | None = None,
) -> str:  # fmt: skip
    """The markdown table of the scan's result."""
    standing = [r for r in rows if r[3] is not None]
    if start[3] is None or not standing:
        return f"{name} ({mesh} mesh): the template's own fold or every fold scanned falls."
    best = min(standing, key=lambda r: r[3])  # type: ignore[arg-type,return-value]
    best_rms = min(standing, key=lambda r: r[4])  # type: ignore[arg-type,return-value]
    span = [sorted({r[k] for r in rows}) for k in (0, 1, 2, 6)]
    ranges = ", ".join(
        f"{n} {v[0]:g}..{v[-1]:g}" if len(v) > 1 else f"{n} {v[0]:g}"
        for n, v in zip(("alpha", "beta", "h_c", "overbend"), span, strict=True)
    )
    knobs = "alpha, beta, h_c" + (", overbend" if len(span[3]) > 1 else "")

    def at(r: Row) -> str:
        return f"{r[0]:g}, {r[1]:g}, {r[2]:g}" + (f", {r[6]:g}" if len(span[3]) > 1 else "")

    assert start[4] is not None
    return "\n".join(
        [
            "| template, mesh | grid (alpha, beta, overbend deg; h_c of R cos(alpha)) | folds "
            f"standing | uncompensated max / rms | a fifth of it | smallest max on the grid "
            f"({knobs}) | smallest rms ({knobs}) | CPU |",
            "|---|---|---|---|---|---|---|---|",
            f"| {name}, {mesh} | {ranges} ({len(rows)}) | {len(standing)} | {start[3]:.4g} / "
            f"{start[4]:.4g} {unit} | {start[3] / 5:.4g} {unit} | {best[3]:.4g} {unit} "
            f"({at(best)}) | {best_rms[4]:.4g} {unit} ({at(best_rms)}) | "
            f"{sum(r[5] for r in rows) + start[5]:.0f} s |",
        ]
        + (
            []
            if polished is None or polished[3] is None
            else [
                "",
                f"Polished from the grid's best by Nelder-Mead on the largest distance itself"
                f"{'' if polished_overbend is None else ' (the crease overbend too)'}: "
                f"{polished[3]:.4g} {unit} at alpha {polished[0]:.4g}, beta {polished[1]:.4g} deg, "
                f"h_c {polished[2]:.3g}"
                + (
                    ""
                    if polished_overbend is None
                    else f", crease overbend {polished_overbend:.3g} deg"
                )
                + f" ({polished[5]:.0f} s CPU).",
            ]
        )
    )


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("template", nargs="?", default="patkau-one-fold")
    ap.add_argument("--alpha", default="30:40:2", help="START:STOP:STEP or A,B,.. (deg)")
    ap.add_argument("--beta", default="26:36:2", help="START:STOP:STEP or A,B,.. (deg)")
    ap.add_argument("--hc", default="0", help="h_c as a fraction of R cos(alpha), as --alpha")
    ap.add_argument("--mesh", default="coarse", choices=("coarse", "normal"))
    ap.add_argument(
        "--polish", type=int, default=0, metavar="N", help="then Nelder-Mead, N simulations"
    )
    ap.add_argument("--overbend", action="store_true", help="polish the crease overbend too")
    ap.add_argument(
        "--overbend-grid", default="0", help="the crease overbend's grid (deg), as --alpha"
    )
    ap.add_argument("-j", "--jobs", type=int, default=2)
    ap.add_argument("--write-docs", action="store_true")
    ns = ap.parse_args()
    design = load_template(find_template(ns.template))
    f = design.frame
    knobs = itertools.product(grid(ns.alpha), grid(ns.beta), grid(ns.hc), grid(ns.overbend_grid))
    tasks = [(ns.template, ns.mesh, a, b, h, o) for a, b, h, o in knobs]
    own_hc = f.h_c / (f.radius * math.cos(math.radians(f.alpha)))
    t0 = time.monotonic()
    with ProcessPoolExecutor(ns.jobs) as ex:
        start = ex.submit(one, (ns.template, ns.mesh, f.alpha, f.beta, own_hc))
        rows = list(ex.map(one, tasks))
    for a, b, h, mx, rms, cpu, o in rows:
        got = "falls" if mx is None else f"max {mx:8.4g}  rms {rms:8.4g}"
        print(f"alpha {a:5.1f}  beta {b:5.1f}  h_c {h:+.2f}  overbend {o:+5.1f}  {got}  "
              f"({cpu:.1f} s CPU)")  # fmt: skip
    standing = [r for r in rows if r[3] is not None]
    polished, overbend = None, None
    if ns.polish and standing:
        best = min(standing, key=lambda r: r[3])  # type: ignore[arg-type,return-value]
        polished, overbend = polish(ns.template, ns.mesh, best, ns.polish, ns.overbend)
    text = summary(ns.template, ns.mesh, design.units.value, start.result(), rows, polished,
                   overbend)  # fmt: skip
    print(f"\n{text}\n\nwall {time.monotonic() - t0:.0f} s")
    if ns.write_docs:
        from docs_block import machine_line, write_block  # type: ignore[import-not-found]

        command = (
            f".venv/bin/python benchmarks/compensate_family.py {ns.template} --alpha {ns.alpha} "
            f"--beta {ns.beta} --hc={ns.hc}"
            + ("" if ns.overbend_grid == "0" else f" --overbend-grid={ns.overbend_grid}")
            + f" --mesh {ns.mesh} --polish {ns.polish}"
            + (" --overbend" if ns.overbend else "")
            + " --write-docs"
        )
        write_block(BLOCK, f"{text}\n\n{machine_line()}", command, path=DOC)


if __name__ == "__main__":
    sys.path.insert(0, str(Path(__file__).resolve().parent))
    main()
