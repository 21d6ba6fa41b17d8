"""Benchmark: build and write the STEP of every shipped template, shell and solid.

For each template: solve + fold (the baseline, measured in the same run), then
building the part (:func:`build_part`) and writing the STEP
(:func:`export_design_step`) for the reference surface ('shell') and, for
exact-model designs with thickness and a relief hole, the sheet's solid;
printed as seconds and as ratios to the baseline, with the face count and the
file size. Asserts nothing about timings.

Run from the repository root::

    .venv/bin/python benchmarks/bench_step.py [--repeat 3] [--only NAME ...]
"""

from __future__ import annotations

import argparse
import sys
import tempfile
from functools import partial
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from bench_solver import best_of, machine_info  # noqa: E402

from onefold_cad import build_design  # noqa: E402
from onefold_cad.export.step import build_part, default_body, export_design_step  # noqa: E402
from onefold_cad.templates import list_templates, load_template  # noqa: E402


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=3, help="best of N runs (default 3)")
    ap.add_argument("--only", nargs="*", help="template names (default: all)")
    args = ap.parse_args(argv)
    infos = [t for t in list_templates() if not args.only or t.name in args.only]
    print("machine: " + ", ".join(f"{k} {v}" for k, v in machine_info().items()))
    print()
    print(
        "| template | body | solve + fold (s) | build (s) | build / solve | write (s) "
        "| write / solve | faces | KiB |"
    )
    print("|---|---|---|---|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as tmp:
        for info in infos:
            design = load_template(info.path)
            folded = build_design(design)
            t_solve = best_of(partial(build_design, design), args.repeat)[0]
            bodies = ["shell"] + (["solid"] if default_body(design) == "solid" else [])
            for body in bodies:
                path = Path(tmp) / f"{design.name}-{body}.step"
                build = partial(build_part, design, folded, body=body)
                t_build, part = best_of(build, args.repeat)
                write = partial(export_design_step, design, path, folded, body=body)
                t_write = best_of(write, args.repeat)[0]
                print(
                    f"| {info.name} | {body} | {t_solve:.2e} | {t_build:.3f} | "
                    f"{t_build / t_solve:.0f}x | {t_write:.3f} | {t_write / t_solve:.0f}x | "
                    f"{len(part.faces())} | {path.stat().st_size / 1024:.0f} |"
                )
    return 0


if __name__ == "__main__":
    sys.exit(main())
