"""The README's sweep, this tree against an earlier commit, in one run.

The command is the README's ``onefold sweep ...`` line (its ``-o`` folder
replaced by a fresh temporary one per run, ``--quiet`` added) in two forms:
as written (the process pool on every core) and with ``-j N`` (``--jobs``,
default 1: the sweep in its own process, whose CPU time the OS then counts
whole; on a shared machine the steadier measure). The earlier tree is
commit ``--baseline`` (default ec17278, main when issue 37's item 9 was
started): its ``onefold_cad/`` and ``templates/`` extracted with ``git
archive`` into a temporary folder and run by the same interpreter with this
checkout's editable install hidden, so only the package differs. The four
runs of a round go in turn (the order rotated every round), each a whole
process, imports included; the OS measures its wall time and CPU time
(wait4). Each cell: median [25th, 75th percentile]; a ratio is the median
of the per-round ratios, baseline over this tree (> 1: this tree is
faster). Whether issue 37's target, 1.25x, is met is printed, never asserted.

Run from the repository root::

    .venv/bin/python benchmarks/bench_readme_sweep.py [--rounds 3] [--baseline ec17278]
        [--jobs 1] [--write-docs]
"""

from __future__ import annotations

import argparse
import shlex
import subprocess
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from docs_block import ROOT, machine_line, write_block  # noqa: E402
from git_baseline import extract  # noqa: E402
from interleave import ProcessRun, Stats, run_process, stats_of  # noqa: E402

#: Issue 37's target: the README's sweep this much faster than the baseline.
TARGET = 1.25
#: main when the work on the sweep's tail started.
BASELINE = "ec17278"

#: Run ``python -m onefold_cad`` from the folder in argv[1], not from the
#: editable install of this checkout (whose import hook would win over
#: sys.path).
_BOOT = """
import runpy, sys
root = sys.argv.pop(1)
sys.meta_path[:] = [f for f in sys.meta_path if "editable" not in repr(f)]
sys.path.insert(0, root)
import onefold_cad
assert onefold_cad.__file__.startswith(root), onefold_cad.__file__
runpy.run_module("onefold_cad", run_name="__main__", alter_sys=True)
"""


def readme_sweep() -> list[str]:
    """The README's ``onefold sweep`` example as arguments (after ``onefold``)."""
    for line in (ROOT / "README.md").read_text().splitlines():
        if line.startswith("onefold sweep "):
            return shlex.split(line.split("#", 1)[0])[1:]
    raise SystemExit("README.md: no 'onefold sweep' line")


def with_output(args: list[str], out: Path, jobs: int | None) -> list[str]:
    """``args`` writing to ``out`` (its ``-o`` value replaced), quiet, with
    ``-j jobs`` unless ``jobs`` is None."""
    out_args = list(args)
    i = out_args.index("-o")
    out_args[i + 1] = str(out)
    return [*out_args, *(["-j", str(jobs)] if jobs else []), "--quiet"]


def _ratio(runs: dict[str, list[ProcessRun]], base: str, ours: str, what: str) -> Stats:
    """The per-round ratios ``base / ours`` of ``what`` (wall or cpu)."""
    pairs = zip(runs[base], runs[ours], strict=True)
    return stats_of([getattr(b, what) / getattr(o, what) for b, o in pairs])


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--baseline", default=BASELINE)
    ap.add_argument("--jobs", type=int, default=1, help="the second form's -j N")
    ap.add_argument("--write-docs", action="store_true")
    args = ap.parse_args(argv)
    sweep = readme_sweep()
    forms = {"as written": None, f"-j {args.jobs}": args.jobs}
    with tempfile.TemporaryDirectory(prefix="bench-readme-sweep-") as tmp_name:
        tmp = Path(tmp_name)
        extract(args.baseline, tmp / "old")
        # its bytecode compiled beforehand, as this tree's is
        subprocess.run([sys.executable, "-m", "compileall", "-q", str(tmp / "old")], check=True)
        boot = tmp / "boot.py"
        boot.write_text(_BOOT)
        trees = {
            "this tree": [sys.executable, "-m", "onefold_cad"],
            args.baseline: [sys.executable, str(boot), str(tmp / "old")],
        }
        cases = [(form, tree) for form in forms for tree in trees]
        runs: dict[str, list[ProcessRun]] = {f"{t}, {f}": [] for f, t in cases}
        for r in range(args.rounds):
            for i, (form, tree) in enumerate(cases[r % 4 :] + cases[: r % 4]):
                out = tmp / f"out-{r}-{i}"
                run = run_process([*trees[tree], *with_output(sweep, out, forms[form])])
                if run.returncode != 0 or not (out / "results.parquet").is_file():
                    raise SystemExit(f"{tree}, {form}: the sweep failed (exit {run.returncode})")
                runs[f"{tree}, {form}"].append(run)
                say = f"  round {r + 1}: {tree}, {form}: {run.wall:.2f} s wall, {run.cpu:.2f} s CPU"
                print(say, file=sys.stderr)
    shown = "onefold " + " ".join(with_output(sweep, Path("DIR"), None))
    lines = [
        machine_line(),
        f"`{shown}` as written (the process pool on every core) and with `-j {args.jobs}`, "
        f"{args.rounds} rounds, the four runs of a round in turn (the order rotated), each a "
        "whole process (imports included). Each cell: median [25th, 75th percentile]; "
        f"ratio: median of the per-round ratios, {args.baseline} over this tree. CPU: the "
        "sweep's process and what it reaped (a pool's workers are the forkserver's children: "
        "not counted).",
        "",
        "| tree, form | wall (s) | CPU (s) |",
        "|---|---|---|",
    ]
    for k, v in runs.items():
        wall, cpu = stats_of([x.wall for x in v]), stats_of([x.cpu for x in v])
        lines.append(f"| {k} | {wall.fmt()} | {cpu.fmt()} |")
    lines.append("")
    for form in forms:
        base, ours = f"{args.baseline}, {form}", f"this tree, {form}"
        wall = _ratio(runs, base, ours, "wall")
        verdict = "met" if wall.median >= TARGET else "not met"
        text = f"{form}: this tree is {wall.fmt(unit='x')} faster on the wall clock ({verdict}"
        if forms[form] == 1:
            cpu = _ratio(runs, base, ours, "cpu")
            verdict = "met" if cpu.median >= TARGET else "not met"
            text += f"), {cpu.fmt(unit='x')} in CPU time ({verdict}"
        lines.append(f"- {text}; target >= {TARGET:g}x).")
    body = "\n".join(lines)
    print(body)
    if args.write_docs:
        given = [a for a in (argv if argv is not None else sys.argv[1:]) if a != "--write-docs"]
        write_block(
            "bench_readme_sweep",
            body,
            ("python benchmarks/bench_readme_sweep.py --write-docs " + " ".join(given)).strip(),
        )
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
