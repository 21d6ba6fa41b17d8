"""Issue 24's three speed targets in one command: the default template's
solid resting placement (at most 10 ms), the sweep on this machine's 2 cores
(at least 100 designs/s) and the explorer's update (at most 50 ms), each by
its own benchmark, which writes its own block of docs/benchmarks.md
(``bench_rest``, ``bench_sweep``, ``bench_explore``); then a summary block
(``bench_scale``) with each target's verdict line, read back from those
blocks, so the summary and the tables come from the same run.

Run from the repository root (about 10 minutes on 2 cores)::

    .venv/bin/python benchmarks/bench_scale.py [--write-docs] [--baseline COMMIT] [--summary-only]

Without ``--write-docs`` the three run and print; nothing is written.
``--summary-only`` runs nothing and rebuilds the summary from the three
blocks as they stand (each keeps its own date and command).
"""

from __future__ import annotations

import argparse
import re
import subprocess
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from docs_block import DOCS, ROOT, machine_line, write_block  # noqa: E402

HERE = Path(__file__).resolve().parent

#: (benchmark, its arguments, the docs block it writes, the target in words)
RUNS = (
    ("bench_rest.py", ["--rounds", "21"], "bench_rest", "resting placement <= 10 ms"),
    (
        "bench_sweep.py",
        ["--designs", "200", "--rounds", "3"],
        "bench_sweep",
        "sweep >= 100 designs/s on 2 cores",
    ),
    (
        "bench_explore.py",
        ["--moves", "20", "--only", "patkau-one-fold"],
        "bench_explore",
        "explorer update <= 50 ms",
    ),
)


def verdict_lines(block: str) -> list[str]:
    """The lines of a generated block that carry a PASS or FAIL; a table row
    comes with its table's header and separator (once per table)."""
    out: list[str] = []
    header: list[str] = []
    shown = False
    previous = ""
    for line in block.splitlines():
        if line.startswith("|") and not previous.startswith("|"):
            header, shown = [line], False  # a new table
        elif line.startswith("|---"):
            header.append(line)
        if re.search(r"\b(PASS|FAIL)\b", line):
            if line.startswith("|") and not shown:
                out += header
                shown = True
            out.append(line)
        previous = line
    return out


def block_text(name: str, path: Path = DOCS) -> str:
    """The body of generated block ``name`` of ``path``."""
    m = re.search(rf"<!-- BEGIN {re.escape(name)} -->\n(.*?)<!-- END {re.escape(name)} -->",
                  path.read_text(), re.S)  # fmt: skip
    if m is None:
        raise SystemExit(f"{path}: no block {name!r}")
    return m.group(1)


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--write-docs", action="store_true")
    ap.add_argument("--baseline", default=None, help="the explorer's --baseline COMMIT")
    ap.add_argument(
        "--summary-only",
        action="store_true",
        help="run nothing: the summary block from the three blocks as they are",
    )
    args = ap.parse_args(argv)
    parts: list[str] = []
    for script, extra, block, target in RUNS:
        cmd = [sys.executable, str(HERE / script), *extra]
        if script == "bench_explore.py" and args.baseline:
            cmd += ["--baseline", args.baseline]
        if args.write_docs:
            cmd.append("--write-docs")
        if args.summary_only:
            out = block_text(block)
        else:
            print("$", " ".join(cmd[1:]), flush=True)
            run = subprocess.run(cmd, cwd=ROOT, check=True, capture_output=True, text=True)
            out = block_text(block) if args.write_docs else run.stdout
            print(run.stdout, flush=True)
        found = verdict_lines(out)
        found = found or ["(no verdict)"]
        parts += [f"**{target}** (`{script}`, its block below):", "", *found, ""]
    body = machine_line() + " The three benchmarks one after the other.\n\n" + "\n".join(parts)
    print(body)
    if args.write_docs:
        extra = f" --baseline {args.baseline}" if args.baseline else ""
        extra += " --summary-only" if args.summary_only else ""
        write_block("bench_scale", body, f"python benchmarks/bench_scale.py --write-docs{extra}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
