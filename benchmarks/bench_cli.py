"""Whole ``onefold`` processes against the bare imports they cannot avoid.

Run from the repository root:

    .venv/bin/python benchmarks/bench_cli.py                # print the table
    .venv/bin/python benchmarks/bench_cli.py --write-docs   # also update docs/benchmarks.md

Every case is a whole process (interpreter start-up and imports included),
run with :func:`interleave.run_process` (wall time, CPU time and peak memory
from the OS). The cases of a group run interleaved, A B C, B C A, ..., so a
burst of load on a shared machine hits them alike; the table gives medians
with the 25th and 75th percentiles, and each command's ratio to its baseline
as the median (and spread) of the per-round ratios.

Targets (issue 14): ``onefold solve`` <= 3x ``python -c "import numpy"`` and
``onefold build patkau-one-fold`` <= 1.6x ``python -c "import build123d"``,
both in wall time. PASS/FAIL is printed, never asserted.
"""

from __future__ import annotations

import argparse
import os
import sys
import tempfile
from dataclasses import dataclass
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from docs_block import machine_line, write_block  # noqa: E402
from interleave import ProcessRun, Stats, run_process, stats_of  # noqa: E402

PY = sys.executable
ONEFOLD = str(Path(PY).parent / "onefold")


@dataclass(frozen=True)
class Case:
    """One command; ``baseline`` names the case it is compared with (or None)."""

    name: str
    argv: tuple[str, ...]
    baseline: str | None = None
    target: float | None = None


def quick_cases() -> list[Case]:
    return [
        Case("python -c pass", (PY, "-c", "pass")),
        Case('python -c "import numpy"', (PY, "-c", "import numpy")),
        Case("onefold --help", (ONEFOLD, "--help"), 'python -c "import numpy"'),
        Case("onefold templates", (ONEFOLD, "templates"), 'python -c "import numpy"'),
        Case("onefold solve", (ONEFOLD, "solve"), 'python -c "import numpy"', 3.0),
        Case("onefold solve --json", (ONEFOLD, "solve", "--json"), 'python -c "import numpy"'),
    ]


def build_cases(outdir: str) -> list[Case]:
    return [
        Case('python -c "import build123d"', (PY, "-c", "import build123d")),
        Case(
            "onefold build patkau-one-fold",
            (ONEFOLD, "build", "patkau-one-fold", "-o", outdir, "-q"),
            'python -c "import build123d"',
            1.6,
        ),
    ]


def measure(cases: list[Case], rounds: int) -> dict[str, list[ProcessRun]]:
    """``rounds`` runs of every case, interleaved with the order rotated each round
    (one untimed warm-up run of each first: file caches, .pyc files, written
    even where the caller's environment sets PYTHONDONTWRITEBYTECODE)."""
    runs: dict[str, list[ProcessRun]] = {c.name: [] for c in cases}
    # bytecode caching on, as in any install: with PYTHONDONTWRITEBYTECODE
    # (set on some CI machines) the warm-up writes no .pyc and every timed
    # run would recompile each module of the package it imports
    env = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"}
    for c in cases:
        run_process(c.argv, env=env)
    for i in range(rounds):
        order = cases[i % len(cases) :] + cases[: i % len(cases)]
        for c in order:
            r = run_process(c.argv, env=env)
            if r.returncode != 0:
                raise SystemExit(f"{c.name} exited with {r.returncode}")
            runs[c.name].append(r)
        print(f"round {i + 1}/{rounds}", file=sys.stderr)
    return runs


def rows(cases: list[Case], runs: dict[str, list[ProcessRun]]) -> list[str]:
    out = []
    for c in cases:
        rs = runs[c.name]
        wall = stats_of([r.wall for r in rs])
        cpu = stats_of([r.cpu for r in rs])
        mem = stats_of([r.peak_rss / 2**20 for r in rs])
        ratio, verdict = "", ""
        if c.baseline is not None:
            base = runs[c.baseline]
            paired: Stats = stats_of([r.wall / b.wall for r, b in zip(rs, base, strict=True)])
            ratio = paired.fmt(unit="x")
            if c.target is not None:
                ok = paired.median <= c.target
                verdict = f"{'PASS' if ok else 'FAIL'} (<= {c.target:g}x)"
        out.append(
            f"| `{c.name}` | {wall.fmt()} | {cpu.fmt()} | {mem.median:.0f} | {ratio} | {verdict} |"
        )
    return out


def render(quick: tuple[list[Case], dict], build: tuple[list[Case], dict] | None) -> str:
    n_quick = len(next(iter(quick[1].values())))
    lines = [
        machine_line(),
        f"Whole processes, interleaved; quick commands {n_quick} rounds"
        + (f", build {len(next(iter(build[1].values())))} rounds" if build else "")
        + ". Each cell: median [25th, 75th percentile]; ratio: median [spread] of the "
        "per-round wall-time ratios to the baseline named.",
        "",
        "| command | wall (s) | CPU (s) | peak memory (MB) | ratio to baseline (wall) | target |",
        "|---|---|---|---|---|---|",
        *rows(*quick),
    ]
    if build:
        lines += rows(*build)
    lines += [
        "",
        "Baselines: `onefold --help`, `templates` and `solve` against "
        '`python -c "import numpy"`; `onefold build` against `python -c "import build123d"`.',
    ]
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--rounds", type=int, default=21, help="rounds of the quick commands")
    ap.add_argument("--build-rounds", type=int, default=5, help="rounds of the build (0: skip)")
    ap.add_argument("--write-docs", action="store_true", help="update docs/benchmarks.md")
    args = ap.parse_args(argv)
    qc = quick_cases()
    quick = (qc, measure(qc, args.rounds))
    build = None
    if args.build_rounds > 0:
        with tempfile.TemporaryDirectory() as tmp:
            bc = build_cases(tmp)
            build = (bc, measure(bc, args.build_rounds))
    text = render(quick, build)
    print(text)
    if args.write_docs:
        cmd = "python benchmarks/bench_cli.py --write-docs"
        if args.rounds != 21:
            cmd += f" --rounds {args.rounds}"
        if args.build_rounds != 5:
            cmd += f" --build-rounds {args.build_rounds}"
        write_block("bench_cli", text, cmd)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
