"""Benchmark the STEP adapter: the solid per template, shells by divisions, whole builds.

Three tables, all timed with :mod:`interleave` (cases run A B C, B C A, ...
so that load on the shared machine hits them alike; medians with the 25th
and 75th percentiles in brackets; CPU time of this process unless noted):

1. per shipped template: the reference-surface shell (:func:`build_shell`)
   and, where the template's default body is the solid, the STEP solid
   (:func:`build_solid`, with its validity and volume checks), with their
   face counts;
2. the paper model's fan shell (Table 1's square, with and without a relief
   hole) at 20, 90, 360, 1000 and 3000 divisions (validity check included);
3. whole processes, wall and CPU time and peak memory, measured by the OS:
   ``onefold build patkau-one-fold`` against a bare
   ``python -c "import build123d"``, run alternately; the ratio is the
   median of the per-round ratios (build / import), with its spread.

Asserts nothing about timings. Run from the repository root::

    .venv/bin/python benchmarks/bench_step.py [--rounds 9] [--process-rounds 7]
        [--parts templates shells processes] [--only TEMPLATE ...] [--divisions N ...]
"""

from __future__ import annotations

import argparse
import os
import shutil
import sys
import tempfile
from functools import partial
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from interleave import interleave, run_process, stats_of  # noqa: E402

from onefold_cad import Design, FrameCurve, Sheet, fold_design  # noqa: E402
from onefold_cad.export.part import build_shell, build_solid
from onefold_cad.fabrication.relief_hole import relief_hole_diameter
from onefold_cad.fabrication.rules import default_body
from onefold_cad.templates import list_templates, load_template  # noqa: E402

DIVISIONS = (20, 90, 360, 1000, 3000)


def templates(rounds: int, names: list[str] | None) -> None:
    print("## STEP shell and solid per template (CPU s per build, median [q1, q3])\n")
    cases, faces = {}, {}
    for info in list_templates():
        if names and info.name not in names:
            continue
        design = load_template(info.path)
        folded = fold_design(design)
        m = design.material.with_changes(relief_hole=relief_hole_diameter(design, folded))
        cases[f"{info.name} shell"] = partial(
            build_shell, folded, relief_hole=m.relief_hole_diameter
        )
        if default_body(design) == "solid":
            cases[f"{info.name} solid"] = partial(build_solid, folded, m)
    for name, build in cases.items():
        faces[name] = len(build().faces())
    stats = interleave(cases, rounds=rounds, batch_time=0.0)
    print("| template | body | faces | CPU s |")
    print("|---|---|---|---|")
    for name, st in stats.items():
        template, body = name.rsplit(" ", 1)
        print(f"| {template} | {body} | {faces[name]} | {st.fmt()} |")
    print()


def shells(rounds: int, divisions: tuple[int, ...]) -> None:
    print("## Paper-model fan shells by divisions (CPU s per build incl. validity)\n")
    square = Sheet.quadrilateral(300, 300, 300, 300)
    cases, faces = {}, {}
    for n in divisions:
        design = Design(f"fan{n}", FrameCurve(50, 45, 0, 100, n), square, model="paper")
        folded = fold_design(design)
        for hole in (0.0, 10.0):
            key = f"{n} {hole:g}"
            cases[key] = partial(build_shell, folded, relief_hole=hole)
            faces[key] = len(cases[key]().faces())
    stats = interleave(cases, rounds=rounds, batch_time=0.0)
    print("| divisions | relief hole | faces | CPU s |")
    print("|---|---|---|---|")
    for key, st in stats.items():
        n, hole = key.split()
        print(f"| {n} | {hole} | {faces[key]} | {st.fmt()} |")
    print()


def processes(rounds: int) -> None:
    print("## Whole processes (wall and CPU s, peak RSS; medians [q1, q3])\n")
    onefold = shutil.which("onefold", path=str(Path(sys.executable).parent)) or "onefold"
    runs: dict[str, list] = {"import": [], "build": []}
    with tempfile.TemporaryDirectory() as tmp:
        commands = {
            "import": [sys.executable, "-c", "import build123d"],
            "build": [onefold, "build", "patkau-one-fold", "-o", os.path.join(tmp, "out")],
        }
        for name in ("import", "build"):  # warm the OS's file cache
            run_process(commands[name])
        for i in range(rounds):
            order = ("import", "build") if i % 2 == 0 else ("build", "import")
            for name in order:
                run = run_process(commands[name])
                if run.returncode != 0:
                    raise SystemExit(f"{' '.join(commands[name])} exited {run.returncode}")
                runs[name].append(run)
    print("| command | wall s | CPU s | peak RSS MiB |")
    print("|---|---|---|---|")
    labels = {
        "import": 'python -c "import build123d"',
        "build": "onefold build patkau-one-fold",
    }
    for name, rs in runs.items():
        wall = stats_of([r.wall for r in rs])
        cpu = stats_of([r.cpu for r in rs])
        rss = stats_of([r.peak_rss / 2**20 for r in rs])
        print(f"| `{labels[name]}` | {wall.fmt()} | {cpu.fmt()} | {rss.fmt(digits=4)} |")
    for clock in ("wall", "cpu"):
        ratio = stats_of(
            [
                getattr(b, clock) / getattr(a, clock)
                for a, b in zip(runs["import"], runs["build"], strict=True)
            ]
        )
        print(f"\nbuild / import ({clock}, per round): {ratio.fmt(unit='x')}")
    print()


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument(
        "--rounds", "--repeat", type=int, default=9, help="interleaved rounds per case (9)"
    )
    ap.add_argument("--process-rounds", type=int, default=7, help="runs of each command (7)")
    ap.add_argument("--divisions", type=int, nargs="*", default=list(DIVISIONS))
    ap.add_argument("--only", nargs="*", help="template names (table 1 only)")
    ap.add_argument(
        "--parts", choices=["templates", "shells", "processes"], nargs="*", help="tables to run"
    )
    args = ap.parse_args(argv)
    parts = args.parts or (["templates"] if args.only else ["templates", "shells", "processes"])
    print(f"machine: {os.cpu_count()} CPUs, load average {os.getloadavg()[0]:.1f} at start\n")
    if "templates" in parts:
        templates(args.rounds, args.only)
    if "shells" in parts:
        shells(args.rounds, tuple(args.divisions))
    if "processes" in parts:
        processes(args.process_rounds)
    return 0


if __name__ == "__main__":
    sys.exit(main())
