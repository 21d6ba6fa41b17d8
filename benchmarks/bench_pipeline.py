"""The whole pipeline per shipped template: solve + fold, flat pattern, each writer.

Run from the repository root:

    .venv/bin/python benchmarks/bench_pipeline.py                # print the table
    .venv/bin/python benchmarks/bench_pipeline.py --write-docs   # also update docs/benchmarks.md

For each template the stages are timed in this process with
:func:`interleave.interleave` (CPU time, the stages interleaved A B C ... with
the order rotated every round, medians with the 25th and 75th percentiles).
The writers are ``onefold build``'s own (:data:`onefold_cad.export.writers.WRITERS`),
each called on a fresh fold and build context (so a writer pays for what it
derives: the flat preview its flat pattern, the report the metrics and the
resting placement) and writing into a temporary folder. The ratio is the median of the
per-round ratios stage / ``solve + fold`` of the same template. Imports are
warmed up before timing (whole processes, imports included, are
``bench_cli.py``'s). A stage that raises a OneFoldError is shown as FAILED
with its message, never skipped.
"""

from __future__ import annotations

import argparse
import sys
import tempfile
from collections.abc import Callable
from pathlib import Path
from typing import Any

sys.path.insert(0, str(Path(__file__).resolve().parent))

from docs_block import machine_line, write_block  # noqa: E402
from interleave import Stats, interleave, paired_ratio  # noqa: E402

from onefold_cad import Design, OneFoldError, fold, solve  # noqa: E402
from onefold_cad.export.writers import WRITERS, BuildContext  # noqa: E402
from onefold_cad.templates import list_templates, load_template  # noqa: E402

CORE = "solve + fold"


def stages(design: Design, out: Path) -> dict[str, Callable[[], Any]]:
    """Stage name -> a call doing that stage once."""
    from onefold_cad.fabrication.flat_pattern import flat_pattern

    def fresh() -> Any:
        # not design.fold_design, which keeps one fold per design object
        return fold(solve(design.frame, design.model), design.sheet)

    folded = fresh()

    def writer(name: str) -> Callable[[], Any]:
        w = WRITERS[name]

        def call() -> Any:
            # a fresh fold: what FoldedSheet derives on first use (metrics, resting
            # placement, the exact model's boundary) is paid by the stage using it
            ctx = BuildContext(design, fresh())
            ctx.files = [out / f"{design.name}{WRITERS[n].suffix}" for n in WRITERS]
            return w.write(ctx, out / f"{design.name}{w.suffix}")

        return call

    return {
        CORE: fresh,
        "flat pattern": lambda: flat_pattern(design, folded),
        **{name: writer(name) for name in WRITERS},
    }


def measure(design: Design, rounds: int, out: Path) -> dict[str, Stats | str]:
    """Stats per stage, or why a stage could not run."""
    cases = stages(design, out)
    res: dict[str, Stats | str] = {}
    for name, fn in list(cases.items()):
        try:
            fn()
        except OneFoldError as exc:
            res[name] = f"FAILED: {str(exc).replace('|', '/')}"
            del cases[name]
    timed = interleave(cases, rounds=rounds, batch_time=0.05)
    for name in cases:
        res[name] = timed[name]
        if name != CORE:
            res[f"{name} ratio"] = paired_ratio(timed, name, CORE)
    return res


def render(results: dict[str, dict[str, Stats | str]], rounds: int) -> str:
    cols = [CORE, "flat pattern", *WRITERS]
    lines = [
        f"{machine_line()} CPU time in this process, {rounds} interleaved rounds per "
        "template. Each cell: median [25th, 75th percentile] seconds, and the median ratio "
        "to the template's solve + fold.",
        "",
        "| template | " + " | ".join(cols) + " |",
        "|---" * (len(cols) + 1) + "|",
    ]
    for name, res in results.items():
        cells = []
        for c in cols:
            v = res.get(c, "missing")
            if isinstance(v, Stats):
                ratio = res.get(f"{c} ratio")
                extra = f" ({ratio.median:.3g}x)" if isinstance(ratio, Stats) else ""
                cells.append(v.fmt() + extra)
            else:
                cells.append(str(v))
        lines.append(f"| {name} | " + " | ".join(cells) + " |")
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--rounds", type=int, default=5, help="interleaved rounds (default 5)")
    ap.add_argument("--only", nargs="*", help="template names (default: all shipped)")
    ap.add_argument("--write-docs", action="store_true", help="update docs/benchmarks.md")
    args = ap.parse_args(argv)
    infos = [i for i in list_templates() if not args.only or i.name in args.only]
    results = {}
    with tempfile.TemporaryDirectory() as tmp:
        for info in infos:
            results[info.name] = measure(load_template(info.path), args.rounds, Path(tmp))
            print(f"{info.name}: done", file=sys.stderr)
    text = render(results, args.rounds)
    print(text)
    if args.write_docs:
        cmd = "python benchmarks/bench_pipeline.py --write-docs" + (
            f" --rounds {args.rounds}" if args.rounds != 5 else ""
        )
        write_block("bench_pipeline", text, cmd)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
